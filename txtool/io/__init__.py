"""Input: safe XML reading, xacro expansion, source positions and the one loading entry."""
