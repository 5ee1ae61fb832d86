"""Cost of a simulate step against the bare Pinocchio work (one rnea plus one aba).

Run: ``python bench/bench_simulate.py [ROBOT.urdf ...]``. Without arguments it measures a
3-DoF arm (simple + differential transmissions), a 6-DoF arm (simple + four-bar + differential)
and, when present, ``fixtures/demo_robot.urdf`` and the corpus UR5e
(``../shared/corpus/universal_robot__ur5e.urdf``). For each robot it reports startup (imports,
loading, model build and the loop's setup) separately, then the per-step wall time of the closed
loop and of a bare ``rnea + aba`` loop over the same states on the same model, and their ratio.
The two are timed in turn, ``--repeat`` times (default 15): the ratio of the best times, the
median of the ratios of each pair, and the median ratio of their CPU times (``process_time``,
which other processes' load disturbs less than wall time). txtool is byte-compiled first, as
installing it does (see ``installed.py``).
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from installed import byte_compile

REPEAT = 15
ROOT = Path(__file__).resolve().parent.parent

LINK = ('<link name="{name}"><inertial><origin xyz="{c} 0 0"/><mass value="{m}"/>'
        '<inertia ixx="0.002" iyy="{i}" izz="{i}" ixy="0" ixz="0" iyz="0"/></inertial></link>')
JOINT = ('<joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/>'
         '<origin xyz="{x} 0 0"/><axis xyz="{axis}"/>'
         '<limit lower="-2" upper="2" effort="{effort}" velocity="3"/></joint>')
SIMPLE = ('<transmission name="t_{j}"><type>transmission_interface/SimpleTransmission</type>'
          '<joint name="{j}"><hardwareInterface>hardware_interface/EffortJointInterface'
          '</hardwareInterface></joint><actuator name="m_{j}"><mechanicalReduction>{n}'
          '</mechanicalReduction></actuator></transmission>')
PAIR = ('<transmission name="t_{a}_{b}"><type>transmission_interface/{kind}</type>'
        '<joint name="{a}"><role>joint1</role><hardwareInterface>hardware_interface/'
        'EffortJointInterface</hardwareInterface></joint>'
        '<joint name="{b}"><role>joint2</role><hardwareInterface>hardware_interface/'
        'EffortJointInterface</hardwareInterface></joint>'
        '<actuator name="m_{a}"><role>actuator1</role><mechanicalReduction>{n}'
        '</mechanicalReduction></actuator><actuator name="m_{b}"><role>actuator2</role>'
        '<mechanicalReduction>{n}</mechanicalReduction></actuator></transmission>')
AXES = ("0 1 0", "0 1 0", "0 0 1", "0 1 0", "1 0 0", "0 1 0")


def arm(n: int) -> str:
    """An n-joint serial arm: joint 1 simple, then pairs as four-bar and differential."""
    parts = [f'<robot name="arm{n}">', '<link name="base"/>']
    for i in range(n):
        mass = 2.0 / (i + 1)
        parts.append(LINK.format(name=f"l{i + 1}", c=0.15, m=mass, i=0.01 / (i + 1)))
        parts.append(JOINT.format(name=f"j{i + 1}", parent="base" if i == 0 else f"l{i}",
                                  child=f"l{i + 1}", x=0.0 if i == 0 else 0.3,
                                  axis=AXES[i % len(AXES)], effort=100.0 / (i + 1)))
    parts.append(SIMPLE.format(j="j1", n=100))
    kinds = ("FourBarLinkageTransmission", "DifferentialTransmission")
    for k, i in enumerate(range(1, n - 1, 2)):
        parts.append(PAIR.format(a=f"j{i + 1}", b=f"j{i + 2}", kind=kinds[k % 2], n=50))
    if n % 2 == 0:
        parts.append(SIMPLE.format(j=f"j{n}", n=30))
    parts.append("</robot>")
    return "\n".join(parts)


def startup_seconds() -> float:
    """Fresh interpreter: import the simulate stack (numpy, pinocchio, lxml, rich)."""
    code = ("import time; t = time.perf_counter(); import txtool.simulation.run, "
            "txtool.simulation.app; print(time.perf_counter() - t)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return float(out.stdout.strip())


def measure(path: str, repeat: int = REPEAT) -> dict[str, float]:
    """Closed loop and bare rnea+aba, interleaved so that both see the same machine load."""
    import numpy as np
    import pinocchio as pin

    from txtool.simulation import loop
    from txtool.simulation.run import Options, finish, prepare

    options = Options(robot=path, allow_saturation=True)
    loops, bares, cpu_ratios = [], [], []
    for _ in range(repeat):
        prepared = prepare(options, None)
        started, cpu = time.perf_counter(), time.process_time()
        loop.run(prepared.plan)
        loops.append(time.perf_counter() - started)
        loop_cpu = time.process_time() - cpu
        plan = prepared.plan
        model = plan.robot.model
        xs = plan.rows[:, plan.slots["x"]]
        qs = np.ascontiguousarray(plan.robot.config(xs) if plan.robot.has_continuous else xs)
        vs = np.ascontiguousarray(plan.rows[:, plan.slots["v"]])
        accs = np.ascontiguousarray(plan.rows[:, plan.slots["a"]])
        taus = np.ascontiguousarray(plan.rows[:, plan.slots["ff"]])
        cpu = time.process_time()
        bares.append(_bare(pin, model, model.createData(), qs, vs, accs, taus))
        cpu_ratios.append(loop_cpu / max(time.process_time() - cpu, 1e-9))
    run = finish(prepared, min(loops))
    return {
        "nv": model.nv, "steps": plan.steps, "setup_s": prepared.setup_s,
        "loop_us": 1e6 * min(loops) / plan.steps, "bare_us": 1e6 * min(bares) / plan.steps,
        "ratio": min(loops) / min(bares),
        "median": statistics.median(a / b for a, b in zip(loops, bares, strict=True)),
        "cpu": statistics.median(cpu_ratios),
        "max_error": max(j.max_error for j in run.joints.values()),
    }


def _bare(pin: object, model: object, data: object, qs: object, vs: object, accs: object,
          taus: object) -> float:
    rnea, aba = pin.rnea, pin.aba  # type: ignore[attr-defined]
    n = len(qs) - 1  # type: ignore[arg-type]
    started = time.perf_counter()
    for k in range(n):
        rnea(model, data, qs[k], vs[k], accs[k])  # type: ignore[index]
        aba(model, data, qs[k], vs[k], taus[k])  # type: ignore[index]
    return time.perf_counter() - started


def main(argv: list[str]) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("robots", nargs="*", help="URDF files (default: the set above)")
    parser.add_argument("--repeat", type=int, default=REPEAT, help="interleaved runs")
    args = parser.parse_args(argv)
    byte_compile()
    paths = list(args.robots)
    with tempfile.TemporaryDirectory() as folder:
        if not paths:
            for n in (3, 6):
                target = Path(folder) / f"arm{n}.urdf"
                target.write_text(arm(n))
                paths.append(str(target))
            demo = ROOT / "fixtures" / "demo_robot.urdf"
            ur5e = ROOT.parent / "shared" / "corpus" / "universal_robot__ur5e.urdf"
            paths += [str(p) for p in (demo, ur5e) if p.is_file()]
        print(f"startup (fresh interpreter, imports): {startup_seconds() * 1e3:.0f} ms")
        print(f"{'robot':24s} {'nv':>3s} {'steps':>6s} {'setup ms':>9s} {'loop us/step':>13s} "
              f"{'rnea+aba us':>12s} {'ratio':>6s} {'median':>7s} {'cpu':>6s} {'max err':>9s}")
        for path in paths:
            r = measure(path, args.repeat)
            print(f"{Path(path).name:24s} {r['nv']:3d} {r['steps']:6d} {r['setup_s'] * 1e3:9.1f} "
                  f"{r['loop_us']:13.2f} {r['bare_us']:12.2f} {r['ratio']:6.2f} "
                  f"{r['median']:7.2f} {r['cpu']:6.2f} {r['max_error']:9.2e}")


if __name__ == "__main__":
    main(sys.argv[1:])
