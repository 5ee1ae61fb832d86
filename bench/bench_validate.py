"""Cost of ``txtool validate``: one file against bare imports, many files against bare parsing.

Run: ``python bench/bench_validate.py [--files N] [--repeat R] [--synthetic] [--jobs J]``.

* **One file.** ``txtool validate ROBOT.urdf`` against
  ``python -c "import click, lxml.etree, pydantic, rich"``, both as fresh processes, runs
  interleaved; median wall time of each and their ratio (budget: at most 1.5).
* **Many files.** N URDFs (default 1,000: the corpus ``.urdf`` files round-robin, or generated
  arms with ``--synthetic`` or when the corpus is absent) in one folder, checked by one
  ``txtool validate`` process, against a bare ``lxml.etree.parse`` of the same files in one
  process. Reports files per second (budget: at least 500) and the ratio of the two wall times
  (budget: at most 3), the ratio of their CPU times (user + system: what other work on a shared
  machine changes least), and the ratio to the parse loop's own time inside its process.
* **Imports.** The modules ``txtool validate`` loads must not include pinocchio, yourdfpy,
  trimesh or numpy.

txtool is byte-compiled first, as installing it does (see ``installed.py``).

Best of R runs for the many-files timings (wall and CPU time each), median of R for the one-file
timings (default 11).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from installed import byte_compile

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "corpus"
HEAVY = ("pinocchio", "pin", "yourdfpy", "trimesh", "numpy")
BASELINE = "import click, lxml.etree, pydantic, rich"
BARE_PARSE = """
import sys, time
from lxml import etree
files = sys.argv[1:]
start = time.perf_counter()
for name in files:
    try:
        etree.parse(name)
    except etree.XMLSyntaxError:
        pass
print(time.perf_counter() - start)
"""

LINK = '<link name="l{i}"><inertial><mass value="1"/></inertial></link>'
JOINT = ('<joint name="j{i}" type="revolute"><parent link="l{p}"/><child link="l{i}"/>'
         '<axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="50" velocity="3"/></joint>')
TRANSMISSION = (
    '<transmission name="t{i}"><type>transmission_interface/SimpleTransmission</type>'
    '<joint name="j{i}"><hardwareInterface>hardware_interface/EffortJointInterface'
    '</hardwareInterface></joint><actuator name="m{i}"><mechanicalReduction>{n}'
    "</mechanicalReduction></actuator></transmission>"
)


def synthetic_arm(dof: int = 7) -> str:
    parts = ['<?xml version="1.0"?>', '<robot name="arm">', LINK.format(i=0)]
    for i in range(1, dof + 1):
        parts += [LINK.format(i=i), JOINT.format(i=i, p=i - 1)]
    parts += [TRANSMISSION.format(i=i, n=50 + i) for i in range(1, dof + 1)]
    return "\n  ".join(parts) + "\n</robot>\n"


def txtool_command() -> list[str]:
    script = Path(sys.executable).with_name("txtool")
    return [str(script)] if script.is_file() else [sys.executable, "-m", "txtool"]


def wall(command: list[str]) -> float:
    return timed(command)[0]


def timed(command: list[str], **run: object) -> tuple[float, float, str]:
    """Wall time, CPU time (user + system) and standard output of one run of ``command``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    out = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                         check=False, **run)  # type: ignore[call-overload]
    elapsed = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return elapsed, cpu, out.stdout


def one_file(robot: Path, repeat: int) -> dict[str, float]:
    base, ours = [], []
    command = [*txtool_command(), "validate", str(robot)]
    for _ in range(repeat):  # interleaved, so load changes hit both alike
        base.append(wall([sys.executable, "-c", BASELINE]))
        ours.append(wall(command))
    return {"baseline_s": statistics.median(base), "validate_s": statistics.median(ours),
            "ratio": statistics.median(ours) / statistics.median(base)}


def sources(synthetic: bool) -> list[tuple[str, str]]:
    if not synthetic and CORPUS.is_dir():
        found = sorted(CORPUS.glob("*.urdf"))
        if found:
            return [(p.name, p.read_text(encoding="utf-8", errors="replace")) for p in found]
    return [("arm.urdf", synthetic_arm())]


def many_files(count: int, repeat: int, synthetic: bool, jobs: int | None = None
               ) -> dict[str, float]:
    folder = Path(tempfile.mkdtemp(prefix="txtool-bench-"))
    try:
        texts = sources(synthetic)
        files = []
        for i in range(count):
            name, text = texts[i % len(texts)]
            path = folder / f"{i:04d}_{name}"
            path.write_text(text, encoding="utf-8")
            files.append(str(path))
        size = sum(os.path.getsize(f) for f in files)
        ours, bare, inside, our_cpu, bare_cpu = [], [], [], [], []
        for _ in range(repeat):
            parallel = ["--jobs", str(jobs)] if jobs else []
            elapsed, cpu, _out = timed([*txtool_command(), "validate", "--format", "json",
                                        *parallel, str(folder)])
            ours.append(elapsed)
            our_cpu.append(cpu)
            elapsed, cpu, out = timed([sys.executable, "-c", BARE_PARSE, *files])
            bare.append(elapsed)
            bare_cpu.append(cpu)
            inside.append(float(out))
        best = min(ours)
        return {"files": count, "megabytes": size / 1e6, "kinds": len(texts),
                "validate_s": best, "files_per_s": count / best,
                "bare_process_s": min(bare), "ratio_to_bare_process": best / min(bare),
                "validate_cpu_s": min(our_cpu), "bare_process_cpu_s": min(bare_cpu),
                "cpu_ratio_to_bare_process": min(our_cpu) / min(bare_cpu),
                "bare_parse_loop_s": min(inside), "ratio_to_parse_loop": best / min(inside)}
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def imported(robot: Path) -> list[str]:
    probe = (
        "import sys\nfrom txtool.cli import cli\n"
        "try:\n    cli.main(sys.argv[1:], prog_name='txtool')\nexcept SystemExit:\n    pass\n"
        "print(sorted({m.split('.')[0] for m in sys.modules}), file=sys.stderr)\n"
    )
    result = subprocess.run([sys.executable, "-c", probe, "validate", str(robot)],
                            capture_output=True, text=True, check=False)
    loaded = result.stderr.strip().splitlines()[-1]
    return [name for name in HEAVY if f"'{name}'" in loaded]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--files", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=11)
    parser.add_argument("--synthetic", action="store_true", help="generated arms, not the corpus")
    parser.add_argument("--jobs", type=int, help="passed to validate (default: its own)")
    args = parser.parse_args()
    package = byte_compile()
    with tempfile.TemporaryDirectory() as folder:
        robot = Path(folder) / "arm.urdf"
        robot.write_text(synthetic_arm())
        single = one_file(robot, args.repeat)
        heavy = imported(robot)
    many = many_files(args.files, max(3, args.repeat // 2), args.synthetic, args.jobs)
    print(f"cpus: {os.cpu_count()}  python: {sys.version.split()[0]}  "
          f"txtool: {package} (byte-compiled)")
    print(f"one file: validate {single['validate_s'] * 1000:.0f} ms, imports "
          f"{single['baseline_s'] * 1000:.0f} ms, ratio {single['ratio']:.2f} (budget 1.5)")
    print(f"{many['files']} files ({many['megabytes']:.1f} MB, {many['kinds']} distinct), "
          f"--jobs {args.jobs or 'default'}: "
          f"{many['validate_s']:.2f} s, {many['files_per_s']:.0f} files/s (budget 500)")
    print(f"  bare lxml parse process {many['bare_process_s']:.2f} s: ratio "
          f"{many['ratio_to_bare_process']:.2f} (budget 3); parse loop alone "
          f"{many['bare_parse_loop_s']:.2f} s: ratio {many['ratio_to_parse_loop']:.2f}")
    print(f"  CPU time: validate {many['validate_cpu_s']:.2f} s, bare parse process "
          f"{many['bare_process_cpu_s']:.2f} s: ratio {many['cpu_ratio_to_bare_process']:.2f}")
    print(f"heavy modules imported by validate: {heavy or 'none'}")
    print(json.dumps({"one_file": single, "many_files": many, "heavy_imports": heavy}))


if __name__ == "__main__":
    main()
