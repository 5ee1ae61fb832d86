"""The lock-free cached property of LintContext: computed once, then a plain attribute."""

from __future__ import annotations

from txtool.io.xmlio import Source, parse_bytes
from txtool.lint.context import LintContext, lazy


class Counted:
    def __init__(self) -> None:
        self.calls = 0

    @lazy
    def value(self) -> int:
        """The number of calls so far."""
        self.calls += 1
        return self.calls * 10


def test_computed_on_first_access_then_read_from_the_instance() -> None:
    first, second = Counted(), Counted()
    assert first.value == 10 and first.value == 10 and first.calls == 1
    assert first.__dict__["value"] == 10
    assert second.calls == 0 and second.value == 10  # each instance its own value


def test_an_assigned_or_deleted_value_behaves_as_with_functools() -> None:
    counted = Counted()
    counted.value = 3
    assert counted.value == 3 and counted.calls == 0
    del counted.value
    assert counted.value == 10 and counted.calls == 1


def test_the_class_attribute_is_the_descriptor_with_its_docstring() -> None:
    assert isinstance(Counted.value, lazy)
    assert Counted.value.__doc__ == "The number of calls so far."


def test_a_context_walks_its_document_once() -> None:
    data = b'<robot name="r"><joint name="j" type="revolute"/></robot>'
    context = LintContext(Source(path="r.urdf", data=data, tree=parse_bytes(data, "r.urdf")))
    walked = context._walked
    assert context._walked is walked and list(context.joint_elements) == ["j"]
    assert context.is_robot
