"""The rule registry: an explicit list of rule modules, loaded on first use.

Each rule is one module ``txtool/rules/txNNN_kebab_name.py`` with ``CODE``, ``NAME``,
``SEVERITY``, ``FIXABLE``, ``check(ctx)`` for a robot document or ``check_controllers(ctx)``
for controller files (and ``fix(root)`` when fixable); its module docstring is its
documentation. To add a rule, write the module and add its name to :data:`RULE_MODULES`.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Iterator
from functools import lru_cache
from types import ModuleType
from typing import TYPE_CHECKING, Any, NamedTuple

from txtool.lint.problem import SEVERITIES, Severity

if TYPE_CHECKING:
    from lxml import etree

    from txtool.lint.context import LintContext
    from txtool.lint.problem import Problem

RULE_MODULES: tuple[str, ...] = (
    # TX0xx: the document itself (produced by the pipeline)
    "tx001_xml_syntax",
    "tx002_xacro_failed",
    "tx003_unused_suppression",
    "tx004_space_before_declaration",
    "tx005_invalid_suppression",
    "tx006_no_transmission",
    "tx007_no_ros2_control",
    # TX1xx: one transmission as its loader reads it
    "tx100_missing_name",
    "tx101_missing_type",
    "tx102_unknown_type",
    "tx103_wrong_member_count",
    "tx104_missing_reduction",
    "tx105_invalid_number",
    "tx106_zero_reduction",
    "tx107_bad_role",
    "tx108_duplicate_name",
    "tx109_shared_member",
    "tx110_missing_interface",
    "tx111_partial_number",
    "tx112_invalid_read_only",
    "tx113_unknown_standard_type",
    # TX2xx-TX4xx: cross-checks against the robot, dialects, ignored values (add below)
    "tx200_unknown_joint",
    "tx201_fixed_joint",
    "tx202_mimic_joint",
    "tx203_interface_mismatch",
    "tx204_unknown_interface",
    "tx205_no_valid_interface",
    "tx206_mimic_command_interface",
    "tx207_actuator_component_joints",
    "tx208_duplicate_component_name",
    "tx209_duplicate_interface",
    "tx210_urdf_refused",
    "tx300_unprefixed_interface",
    "tx301_interface_on_actuator",
    "tx302_legacy_type_attribute",
    "tx303_wrong_dialect_tag",
    "tx304_outside_ros2_control",
    "tx305_unread_transmission",
    "tx306_ros1_gazebo_plugin",
    "tx400_ignored_value",
    "tx401_role_order_mismatch",
    "tx402_four_bar_effort_ros1",
    "tx403_singular_transmission",
    "tx404_ros1_members_against_roles",
    # TX5xx: controller configurations against the robot (run by lint.controller_files)
    "tx500_controller_joint_not_driven",
    "tx501_controller_command_interface",
    "tx502_controller_state_interface",
    "tx503_unknown_controller_type",
    "tx504_controllers_claim_one_interface",
)


class UnknownRule(KeyError):
    def __str__(self) -> str:
        return f"no such rule: {self.args[0]}"


class Rule(NamedTuple):
    """One registered rule: its metadata, its functions and its documentation."""

    code: str
    name: str
    severity: Severity
    fixable: bool
    module: ModuleType

    @property
    def check(self) -> Callable[[LintContext], Iterator[Problem]] | None:
        """What it finds in a robot document (None: a rule about controller files only)."""
        return getattr(self.module, "check", None)

    @property
    def defers_to(self) -> tuple[str, ...]:
        """The rules whose running changes what this one reports (``DEFERS_TO``: it leaves a
        finding to one of them while it runs, :meth:`txtool.lint.context.LintContext.runs`)."""
        return tuple(getattr(self.module, "DEFERS_TO", ()))

    @property
    def fix(self) -> Callable[[etree._Element], int] | None:
        return getattr(self.module, "fix", None) if self.fixable else None

    @property
    def options(self) -> Any:
        """The rule's pydantic options model, or None when it takes no options.

        A rule with options has ``options_model()``, which builds the model on first use:
        pydantic's model machinery costs more than linting a file, and most runs need none.
        """
        build = getattr(self.module, "options_model", None)
        return build() if build is not None else None

    @property
    def doc(self) -> str:
        return (self.module.__doc__ or "").strip()

    @property
    def summary(self) -> str:
        """The first sentence of the documentation (one line)."""
        first = self.doc.split("\n\n", 1)[0]
        return " ".join(first.split())


def _load(module_name: str) -> Rule:
    module = importlib.import_module(f"{__name__}.{module_name}")
    rule = Rule(
        code=module.CODE,
        name=module.NAME,
        severity=module.SEVERITY,
        fixable=bool(getattr(module, "FIXABLE", False)),
        module=module,
    )
    _check_contract(module_name, rule)
    return rule


def _check_contract(module_name: str, rule: Rule) -> None:
    expected = f"{rule.code.lower()}_{rule.name.replace('-', '_')}"
    if module_name != expected:
        raise ValueError(f"rule module {module_name} should be named {expected}")
    if rule.severity not in SEVERITIES:
        raise ValueError(f"{rule.code}: severity {rule.severity!r} is not one of {SEVERITIES}")
    if rule.check is None and not hasattr(rule.module, "check_controllers"):
        raise ValueError(f"{rule.code}: neither check() nor check_controllers()")
    if rule.fixable and rule.fix is None:
        raise ValueError(f"{rule.code}: FIXABLE but no fix() function")


@lru_cache(maxsize=1)
def all_rules() -> dict[str, Rule]:
    """Every registered rule by code, in code order."""
    rules = [_load(name) for name in RULE_MODULES]
    by_code: dict[str, Rule] = {}
    for rule in sorted(rules, key=lambda r: r.code):
        if rule.code in by_code:
            raise ValueError(f"rule code {rule.code} is registered twice")
        by_code[rule.code] = rule
    return by_code


def get(code: str) -> Rule:
    """The rule with ``code`` (case-insensitive) or its kebab name; :class:`UnknownRule`."""
    rules = all_rules()
    wanted = code.strip()
    if wanted.upper() in rules:
        return rules[wanted.upper()]
    for rule in rules.values():
        if rule.name == wanted.lower():
            return rule
    raise UnknownRule(code)


def codes() -> tuple[str, ...]:
    return tuple(all_rules())
