from __future__ import annotations

import pytest
from click.testing import CliRunner

from txtool.cli import cli

BROKEN = """<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="m"><mechanicalReduction>0</mechanicalReduction></actuator>
  </transmission>
  <transmission name="u">
    <type>SimpleTansmission</type>
  </transmission>
</robot>
"""
WARNING_ONLY = BROKEN.replace(">0<", ">50<")
CLEAN = WARNING_ONLY.replace(
    """  <transmission name="u">
    <type>SimpleTansmission</type>
  </transmission>
""",
    "",
)


@pytest.fixture
def validate(monkeypatch):
    """Run ``txtool validate ARGS`` outside GitHub Actions; (exit code, stdout, stderr)."""
    monkeypatch.delenv("GITHUB_ACTIONS", raising=False)
    monkeypatch.delenv("NO_COLOR", raising=False)

    def invoke(*args: str, input: str | None = None):
        result = CliRunner().invoke(cli, ["validate", *args], input=input)
        if result.exception and not isinstance(result.exception, SystemExit):
            raise result.exception
        return result.exit_code, result.stdout, result.stderr

    return invoke


@pytest.fixture
def broken(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text(BROKEN)
    return path
