"""The build definition (golden/cube4/builds.py) against the Verilog.

Fails when a Verilog file (rtl/, the vendor layer, the simulation harnesses) declares a
build option or one of cube4_top's widths with another default than the definition's,
when cube4_top elaborates a combination the rules refuse, or refuses one they accept
(Verilator's elaboration, as `make lint` runs it). The named builds and one violation
per rule run here; every one of the 2^7 option combinations runs in `make regress`."""

from __future__ import annotations

import itertools
import re
import subprocess
import sys
from pathlib import Path

import pytest

from cube4.builds import BUILD_PARAMS, FULL_BUILD, NAMED, OPTIONS, RULES, Rule, check_build, complete_build
from cube4.config import Cube4Config
from cube4.errors import UserError

ROOT = Path(__file__).resolve().parents[1]
VERILATOR = Path(sys.prefix) / "bin" / "verilator"
VERILOG = sorted([*ROOT.glob("rtl/*.v"), *ROOT.glob("rtl/*.vh"), *ROOT.glob("rtl/ecp5/*.v"),
                  *ROOT.glob("sim/hdl/*.v"), *ROOT.glob("tb/*/*.v")])
_PARAM = re.compile(r"\bparameter\s+integer\s+(\w+)\s*=\s*(\d+)")
# a small cube4_top: elaboration checks only (P = 1, a 16^3 size class)
SMALL = {"P": 1, "MAX_DIM": 16, "DEPTH": 64, "ADDR_W": 6}


_DEFINE = re.compile(r"^`define\s+(\w+)[ \t]*((?:[^\n]*\\\n)*[^\n]*)", re.M)
_USE = re.compile(r"`(\w+)\b(?!\s*\()")


def _uncommented(text: str) -> str:
    return re.sub(r"//[^\n]*|/\*.*?\*/", "", text, flags=re.S)


def header_macros() -> dict[str, str]:
    """NAME -> body of every argument-free `define of rtl/*.vh (the parameter lists such
    as CUBE4_BUILD_PARAMS are macros there)."""
    macros = {}
    for path in ROOT.glob("rtl/*.vh"):
        for name, body in _DEFINE.findall(_uncommented(path.read_text())):
            if not body.startswith("("):
                macros[name] = body.replace("\\\n", "\n")
    return macros


def declared_defaults(path: Path, macros: dict[str, str] | None = None) -> dict[str, int]:
    """NAME -> default of every `parameter integer NAME = <number>` in a Verilog file,
    with the header macros it uses expanded (nested ones too)."""
    macros = header_macros() if macros is None else macros
    code = _uncommented(path.read_text())
    for _ in range(8):
        code = _USE.sub(lambda m: macros.get(m.group(1), m.group(0)), code)
    return {name: int(value) for name, value in _PARAM.findall(code)}


def test_the_block_parameter_list_is_expanded():
    """CUBE4_BUILD_PARAMS declares every build option: the check below reads through it."""
    found = declared_defaults(ROOT / "rtl" / "cube4_sha.v")
    assert set(BUILD_PARAMS) <= set(found) and "CARRY_SAMPLE" in found


def test_verilog_defaults_are_the_full_build():
    """Every declaration of a build option in rtl/, the vendor layer and the harnesses
    has the full build's value; cube4_top and its harness default to a default Cube4Config's
    widths."""
    widths = Cube4Config().widths()
    seen, wrong, macros = set(), [], header_macros()
    for path in VERILOG:
        found = declared_defaults(path, macros)
        for name, value in found.items():
            if name in FULL_BUILD:
                seen.add(name)
                if value != FULL_BUILD[name]:
                    wrong.append(f"{path.relative_to(ROOT)}: {name} = {value}, the definition says {FULL_BUILD[name]}")
        if path.name in ("cube4_top.v", "cube4_top_harness.v"):
            for name, value in widths.items():
                if found.get(name) != value:
                    wrong.append(f"{path.relative_to(ROOT)}: {name} = {found.get(name)}, Cube4Config says {value}")
    assert not wrong, "\n".join(wrong)
    assert seen == set(BUILD_PARAMS), f"options declared nowhere: {set(BUILD_PARAMS) - seen}"
    top = declared_defaults(ROOT / "rtl" / "cube4_top.v")
    assert all(name in top for name in BUILD_PARAMS), "cube4_top declares every build option"


def test_the_definition_reads_as_documented():
    assert FULL_BUILD == {o.name: o.full for o in OPTIONS}
    assert complete_build(None) == FULL_BUILD
    assert complete_build({"COMPOSITING": 0})["PLW"] == 0           # PLW follows, unless named
    assert complete_build({"RECTS": 1})["PLW"] == 0
    with pytest.raises(UserError, match="PLW = 1 needs COMPOSITING"):
        check_build(complete_build({"COMPOSITING": 0, "SHADING": 0, "PLW": 1}))
    with pytest.raises(UserError, match="MAX_SS_LOG2 = 0"):
        check_build(complete_build({"RECTS": 1}), {"MAX_SS_LOG2": 1})
    with pytest.raises(UserError, match="unknown build option"):
        complete_build({"FOO": 1})
    with pytest.raises(UserError, match="sets each of"):
        check_build({**FULL_BUILD, "CLIP": 2})


def violation(rule: Rule) -> dict[str, int]:
    """The combination nearest the full build (fewest options changed) that breaks ``rule``
    and no other (MAX_SS_LOG2, where a rule names it, 0 or 1)."""
    extra = sorted({k for r in RULES for k in (r.then or {}) if k not in BUILD_PARAMS})
    candidates = []
    for bits in itertools.product((0, 1), repeat=len(BUILD_PARAMS) + len(extra)):
        values = dict(zip((*BUILD_PARAMS, *extra), bits))
        if rule_breaks(values) == [rule]:
            candidates.append((sum(values[k] != FULL_BUILD[k] for k in BUILD_PARAMS) + sum(bits[len(BUILD_PARAMS):]),
                               bits, values))
    assert candidates, f"no combination breaks only: {rule.message()}"
    return min(candidates)[2]


def elaborate(params: dict[str, int]) -> subprocess.CompletedProcess:
    sources = [ROOT / "rtl" / line.split("#", 1)[0].strip()
               for line in (ROOT / "rtl" / "sources.f").read_text().splitlines() if line.split("#", 1)[0].strip()]
    cmd = [str(VERILATOR), "--lint-only", "-Wall", "--quiet", f"-I{ROOT / 'rtl'}", "--top-module", "cube4_top",
           *(f"-G{k}={v}" for k, v in {**SMALL, **params}.items()),
           str(ROOT / "rtl" / "lint_waivers.vlt"), *map(str, sources)]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=300)


def rule_breaks(values: dict[str, int]) -> list[Rule]:
    build = {k: values[k] for k in BUILD_PARAMS}
    widths = {k: v for k, v in values.items() if k not in BUILD_PARAMS}
    return [r for r in RULES if not r.holds(build, widths)]


@pytest.mark.parametrize("rule", RULES, ids=[r.why.split(" ")[0] + "_" + "_".join(r.when) for r in RULES])
def test_cube4_top_refuses_what_a_rule_refuses(rule):
    values = violation(rule)
    assert rule_breaks(values) == [rule]
    res = elaborate(values)
    assert res.returncode != 0, f"cube4_top elaborated {values}, which the rule refuses: {rule.message()}"
    errors = [line for line in res.stderr.splitlines() if "USERERROR" in line]
    assert errors, res.stderr[-2000:]
    assert all(name in " ".join(errors) for name in rule.when), (rule.message(), errors)


@pytest.mark.parametrize("name", list(NAMED))
def test_cube4_top_elaborates_every_named_build(name):
    res = elaborate(NAMED[name])
    assert res.returncode == 0, res.stderr[-2000:]


@pytest.mark.regress
@pytest.mark.parametrize("bits", list(itertools.product((0, 1), repeat=len(BUILD_PARAMS))),
                         ids=lambda b: "".join(map(str, b)))
def test_cube4_top_agrees_with_the_rules_on_every_combination(bits):
    values = dict(zip(BUILD_PARAMS, bits))
    legal = not rule_breaks(values)
    res = elaborate(values)
    assert (res.returncode == 0) == legal, (values, legal, res.stderr[-1500:])
