"""Generated robots whose ``<ros2_control>`` transmissions probe the parser's reading.

Deterministic: every variant comes from a fixed list or from ``random.Random(SEED)``, so a
failure names a variant that the next run builds again.
"""

from __future__ import annotations

import random
from collections.abc import Iterator

SEED = 20260807

# Number spellings (ros2_control lexical_casts.cpp impl::stod after component_parser.cpp strips
# " \t\n\r\f\v"): what istringstream and from_chars read alike, and where they differ.
NUMBERS = (
    "2", "+2", "-2", "2.", ".5", "-.5", "+.5", ".", "+", "-", "", "0", "-0", "+0", "00012",
    "1e3", "1E3", "1e+3", "1e-3", "1e", "1e+", "1.5e", "1ex", "1e3x", "1e400", "-1e400",
    "1e-400", "-1e-400", "1e-310", "2e-324", "3e-324", "4.9e-324",
    "2.2250738585072011e-308", "2.2250738585072014e-308", "1.7976931348623157e308",
    "1.7976931348623159e308", "0x1p3", "0X10", "0x", "inf", "-inf", "+inf", "infinity",
    "nan", "NaN", "nan(1)", "-nan", "1x", "2abc", "1,5", "1_0", "1..2", "++1", "+-1", "-+1",
    "--1", " 2", "2 ", "\t2\n", "\v2\f", "2\v", "\f-3\r", "\u00a02", "2\u00a0", "\u0662",
    "0.1", "0.30000000000000004", "123456789012345678901234567890", "1e22", "9007199254740993",
    "-0.0e-999", "0e99999999999999999999", "1e99999999999999999999",
    "1e-99999999999999999999",
)
# How the number element is written around its text (NUM stands for the text).
ELEMENT_FORMS = (
    "<{tag}>NUM</{tag}>",
    "<{tag}><!-- c -->NUM</{tag}>",
    "<{tag}> <!-- c --> NUM</{tag}>",
    "<{tag}><!-- a --><!-- b -->NUM</{tag}>",
    "<{tag}>NUM<!-- after --></{tag}>",
    "<{tag}>NUM<!-- split -->5</{tag}>",
    "<{tag}><!-- only --></{tag}>",
    "<{tag}/>",
    "<{tag}>   </{tag}>",
    "<{tag}></{tag}><{tag}>NUM</{tag}>",
    "<{tag}><!-- c --></{tag}><{tag}>NUM</{tag}>",
    "<{tag}>junk</{tag}><{tag}>NUM</{tag}>",
    "<{tag}>NUM</{tag}><{tag}>7</{tag}>",
    "<{tag}><![CDATA[NUM]]></{tag}>",
)
# A processing instruction inside the document: tinyxml2 refuses the whole URDF
# (XML_ERROR_PARSING_DECLARATION), so only the fixed variants carry it.
PI_FORM = "<{tag}><?pi x?>NUM</{tag}>"
SPACES = ("", " ", "  ", "\t", "\n ", " \r\n")


def robot(component: str, body: str, joints: tuple[str, ...] = ("j1", "j2")) -> str:
    """A valid URDF whose one ``<ros2_control>`` has ``component`` attributes and ``body``."""
    urdf_joints = "".join(
        f'<joint name="{j}" type="revolute"><parent link="base"/><child link="l{i}"/>'
        f'<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        f'<link name="l{i}"/>'
        for i, j in enumerate(joints)
    )
    declared = "".join(
        f'<joint name="{j}"><command_interface name="position"/>'
        f'<state_interface name="position"/></joint>'
        for j in joints
    )
    return (f'<?xml version="1.0"?>\n<robot name="r"><link name="base"/>{urdf_joints}'
            f"<ros2_control {component}><hardware><plugin>mock/Hw</plugin></hardware>"
            f"{declared}{body}</ros2_control></robot>\n")


def member(tag: str, name: str, role: str, extra: str = "", inner: str = "") -> str:
    return f'<{tag} name="{name}" role="{role}"{extra}>{inner}</{tag}>'


def simple(joint: str, actuator: str = "", plugin: str = "SimpleTransmission",
           name: str = "t") -> str:
    return (f'<transmission name="{name}"><plugin>transmission_interface/{plugin}</plugin>'
            f"{joint}{actuator}</transmission>")


def coupled(kind: str, joints: list[str], actuators: list[str], name: str = "t") -> str:
    return (f'<transmission name="{name}"><plugin>transmission_interface/{kind}</plugin>'
            + "".join(joints) + "".join(actuators) + "</transmission>")


def number_variants() -> Iterator[tuple[str, str]]:
    """Every number spelling as a simple joint's reduction and offset, and inside every
    element form."""
    system = 'name="s" type="system"'
    for text in NUMBERS:
        reduction = f"<mechanical_reduction>{text}</mechanical_reduction>"
        offset = f"<offset>{text}</offset>"
        yield (f"reduction {text!r}",
               robot(system, simple(member("joint", "j1", "joint1", inner=reduction))))
        yield (f"offset {text!r}",
               robot(system, simple(member("joint", "j1", "joint1", inner=offset))))
    for form in (*ELEMENT_FORMS, PI_FORM):
        for text in ("2", "+-1", "1e-400", " 3 "):
            inner = form.format(tag="mechanical_reduction").replace("NUM", text)
            yield (f"form {form!r} {text!r}",
                   robot(system, simple(member("joint", "j1", "joint1", inner=inner))))


def attribute_variants() -> Iterator[tuple[str, str]]:
    """Whitespace around names, roles and read_only; read_only values; missing attributes."""
    system = 'name="s" type="system"'
    for before in SPACES:
        for after in SPACES[:3]:
            name = f"{before}j1{after}"
            yield (f"joint name {name!r}",
                   robot(system, simple(member("joint", name, "joint1"))))
            yield (f"role {before + 'joint1' + after!r}",
                   robot(system, simple(member("joint", "j1", before + "joint1" + after))))
            yield (f"component type {before + 'actuator' + after!r}",
                   robot(f'name="a" type="{before}actuator{after}"',
                         simple(member("joint", "j1", "joint1")), ("j1",)))
    for value in ("true", "false", "True", "FALSE", " true ", "\ttrue\n", "yes", "1", "",
                  "tru", "true\u00a0"):
        for tag in ("joint", "actuator"):
            extra = f' read_only="{value}"'
            joint = member("joint", "j1", "joint1", extra if tag == "joint" else "")
            actuator = member("actuator", "a1", "actuator1", extra if tag == "actuator" else "")
            yield (f"{tag} read_only {value!r}", robot(system, simple(joint, actuator)))
    yield ("joint without role",
           robot(system, simple('<joint name="j1"><role>joint1</role></joint>')))
    yield ("actuator without role", robot(system, simple(
        member("joint", "j1", "joint1"), '<actuator name="a1"/>')))
    yield ("member without name", robot(system, simple('<joint role="joint1"/>')))
    yield ("transmission without name", robot(system, simple(
        member("joint", "j1", "joint1")).replace(' name="t"', "")))
    yield ("transmission without plugin", robot(
        system, f'<transmission name="t">{member("joint", "j1", "joint1")}</transmission>'))
    yield ("plugin after a comment", robot(system, simple(member("joint", "j1", "joint1"))
           .replace("<plugin>", "<plugin><!-- c -->")))
    yield ("plugin with spaces", robot(system, simple(member("joint", "j1", "joint1"))
           .replace("<plugin>", "<plugin> \n ").replace("</plugin>", " \t</plugin>")))
    yield ("undeclared joint", robot(system, simple(member("joint", "j9", "joint1"))))
    yield ("two plugins", robot(system, simple(member("joint", "j1", "joint1")).replace(
        "</plugin>", "</plugin><plugin>transmission_interface/DifferentialTransmission</plugin>",
        1)))
    yield ("empty plugin", robot(system, simple(member("joint", "j1", "joint1")).replace(
        "transmission_interface/SimpleTransmission", "")))
    yield ("tab inside a name", robot(system, simple(member("joint", "j&#9;1", "joint1")),
                                      ("j&#9;1",)))
    yield ("newline inside a name", robot(system, simple(member("joint", "j\n1", "joint1"))))
    yield ("spaced transmission name", robot(system, simple(member("joint", "j1", "joint1"),
                                                            name=" t ")))
    yield ("role written twice", robot(system, simple(
        '<joint name="j1" role="joint1"><role>joint2</role></joint>')))


def component_variants() -> Iterator[tuple[str, str]]:
    """Actuator and system components, member counts, reordered members and roles."""
    reduction = "<mechanical_reduction>{}</mechanical_reduction><offset>{}</offset>"
    for kind in ("DifferentialTransmission", "FourBarLinkageTransmission"):
        for order in ((0, 1), (1, 0)):
            for roles in ((0, 1), (1, 0), (0, 0)):
                joints = [member("joint", f"j{i + 1}", f"joint{roles[k] + 1}",
                                 inner=reduction.format(i + 2, i / 4))
                          for k, i in enumerate(order)]
                actuators = [member("actuator", name, f"actuator{roles[k] + 1}",
                                    inner=f"<mechanical_reduction>{k + 5}</mechanical_reduction>")
                             for k, name in enumerate(("zz", "aa")[::1 if order == (0, 1) else -1])]
                label = f"{kind} order {order} roles {roles}"
                yield label, robot('name="s" type="system"', coupled(kind, joints, actuators))
                yield (label + " in an actuator component",
                       robot('name="a" type="actuator"', coupled(kind, joints, actuators)))
        two = [member("joint", "j1", "joint1"), member("joint", "j2", "joint2")]
        acts = [member("actuator", "a1", "actuator1"), member("actuator", "a2", "actuator2")]
        yield f"{kind} one actuator", robot('name="s" type="system"', coupled(kind, two, acts[:1]))
        yield f"{kind} one joint", robot('name="s" type="system"', coupled(kind, two[:1], acts))
        yield (f"{kind} a repeated joint", robot('name="s" type="system"',
                                                 coupled(kind, [two[0], two[0]], acts)))
        yield (f"{kind} three joints", robot('name="s" type="system"', coupled(
            kind, [*two, member("joint", "j3", "joint2")], acts), ("j1", "j2", "j3")))
        yield (f"{kind} an actuator listed again as a third", robot('name="s" type="system"',
               coupled(kind, two, [*acts, member("actuator", "a1", "actuator1")])))
        yield (f"{kind} a joint listed again as a third", robot('name="s" type="system"',
               coupled(kind, [*two, member("joint", "j1", "joint1")], acts)))
        yield (f"{kind} a repeated actuator", robot('name="s" type="system"',
                                                    coupled(kind, two, [acts[0], acts[0]])))
        yield (f"{kind} reduction zero", robot('name="s" type="system"', coupled(
            kind, two, [member("actuator", "a1", "actuator1",
                               inner="<mechanical_reduction>0</mechanical_reduction>"),
                        acts[1]])))
    one = member("joint", "j1", "joint1", inner="<mechanical_reduction>3</mechanical_reduction>")
    for component in ('name="a" type="actuator"', 'name="s" type="system"',
                      'name="s" type="sensor"'):
        for actuator in ("", member("actuator", "m", "actuator1")):
            yield (f"simple in {component} {'with' if actuator else 'without'} actuator",
                   robot(component, simple(one, actuator), ("j1",)))
    yield ("simple without joint", robot('name="s" type="system"', simple("")))
    yield ("simple with two joints", robot('name="s" type="system"', simple(
        one + member("joint", "j2", "joint2"), member("actuator", "m", "actuator1"))))
    yield ("simple with a repeated joint", robot('name="s" type="system"', simple(
        one + one, member("actuator", "m", "actuator1"))))
    yield ("simple with two actuators", robot('name="s" type="system"', simple(
        one, member("actuator", "m", "actuator1") + member("actuator", "n", "actuator2"))))
    yield ("simple with zero reduction", robot('name="s" type="system"', simple(member(
        "joint", "j1", "joint1", inner="<mechanical_reduction>0</mechanical_reduction>"))))
    yield ("simple actuator component two joints", robot('name="a" type="actuator"', simple(
        one + member("joint", "j2", "joint2"))))
    yield ("two transmissions", robot('name="s" type="system"', simple(one, name="t1")
                                      + simple(member("joint", "j2", "joint1"), name="t2")))
    yield ("custom plugin in an actuator component", robot(
        'name="a" type="actuator"', simple(one, plugin="Custom"), ("j1",)))


def random_variants(count: int) -> Iterator[tuple[str, str]]:
    """Coupled transmissions with random spellings, element forms and member orders."""
    rng = random.Random(SEED)
    kinds = ("DifferentialTransmission", "FourBarLinkageTransmission", "SimpleTransmission")
    for index in range(count):
        kind = rng.choice(kinds)
        members = []
        for tag, names in (("joint", ("j1", "j2")), ("actuator", ("b", "a"))):
            for k, name in enumerate(names):
                inner = ""
                for field in ("mechanical_reduction", "offset"):
                    if rng.random() < 0.7:
                        form = rng.choice(ELEMENT_FORMS).format(tag=field)
                        inner += form.replace("NUM", rng.choice(NUMBERS))
                spaced = rng.choice(SPACES[:3]) + name + rng.choice(SPACES[:3])
                members.append(member(tag, spaced, f"{tag}{k + 1}", inner=inner))
        rng.shuffle(members)
        body = coupled(kind, members[:], [])
        component = ('name="a" type="actuator"' if rng.random() < 0.15
                     else 'name="s" type="system"')
        yield f"random {index}", robot(component, body)


def all_variants(random_count: int = 200) -> list[tuple[str, str]]:
    return [*number_variants(), *attribute_variants(), *component_variants(),
            *random_variants(random_count)]
