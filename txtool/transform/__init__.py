"""Transforms that produce documents: conversion between dialects, migration, round trips, BB."""
