"""Late register inputs of one nextpnr run, grouped by register: where a build fails its clock.

nextpnr's final timing report names one critical path per clock; a build that fails by a
few percent can have dozens of independent late paths behind it. With
``--detailed-timing-report`` nextpnr's JSON report (``--report``) lists, for the nets it
times, the arrival time at each sink (ns from the launching clock edge). This reads that
list and keeps the register inputs whose arrival exceeds the clock period: a flip-flop's
DI, CE, LSR or M, a distributed RAM's write data, address or enable, and a multiplier's A
or B. The sink's setup time is not counted (nextpnr's ECP5 flip-flop setup is 0; block
inputs have some), so these are late inputs, at least. Lane and copy indices in the names
are merged (``u_com.g_lane[3].rgba_l`` and ``u_com.g_lane[5].rgba_l`` are one group), and
the suffixes synthesis adds are stripped, so a group is one register of the RTL.

nextpnr's detailed list does not hold every net of the design (on the P = 8 build the first
net of the critical path was absent), so a count here is a lower bound.

    make fpga FPGA_ARGS="--p 8 --seeds 1,2 --detailed-timing --no-budget --json build/reports/p8.json --md build/reports/p8.md"
    python -m cube4_reports.endpoints build/synth/fpga/p8_d128_w1024/seed1/report.json --freq 125

Each group shows which of its ports are late (a clock enable ``CE``, data ``DI``/``M``, a
multiplier's operand pins ``A``/``B``, a distributed RAM's ``WD``/``WAD``/``WRE``). With
``--inputs REGEX`` the late inputs of the groups the regex matches are listed one by one,
with the cell that drives each (the last cell of its path):

    python -m cube4_reports.endpoints .../seed1/report.json --freq 125 --inputs 'u_gra.h1_b'
"""

from __future__ import annotations

import argparse
import json
import re
from collections import Counter
from pathlib import Path

from .fpga import DEFAULT_FREQ, signal_stem, unit_of_name
from .synth import UserError, cli_main

# register inputs by port name (the ECP5 cells nextpnr times: TRELLIS_FF, the write side of a
# distributed RAM, MULT18X18D); a flip-flop's M only on a flip-flop cell
REG_PORT = re.compile(r"^(DI|CE|LSR|WD\d?|WAD\d|WRE)$")
FF_CELL = re.compile(r"_TRELLIS_FF_Q(_\d+)?$")
DSP_PORT = re.compile(r"^[AB]\d+$")


def is_register_input(cell: str, port: str) -> bool:
    """Whether a sink is a register input (see the module's docstring)."""
    if REG_PORT.match(port):
        return True
    if port == "M":
        return bool(FF_CELL.search(cell))
    return ".u_mult" in cell and bool(DSP_PORT.match(port))


def group_of(cell: str) -> str:
    """'u_com.g_lane[3].rgba_l_TRELLIS_FF_Q_120' -> 'u_com.g_lane[*].rgba_l': the report's
    signal stem (synthesis's suffixes stripped) without what packing appends after a '$'
    (a distributed RAM's '$DPRAM_COMB1'), lane and copy indices merged."""
    return re.sub(r"\[\d+\]", "[*]", signal_stem(cell.split("$", 1)[0]))


def arrival(sink: dict) -> float:
    """The latest arrival at a sink ('delay' is [min, max] in nextpnr 0.11, a number before)."""
    d = sink["delay"]
    return float(max(d)) if isinstance(d, list) else float(d)


def port_kind(port: str) -> str:
    """'A17' -> 'A', 'WAD2' -> 'WAD', 'DI' -> 'DI': a port without its bit index."""
    return port.rstrip("0123456789") or port


def late_inputs(report: dict, period_ns: float) -> list[dict]:
    """Every register input arriving after period_ns: [{group, cell, port, driver, ns}], the
    latest first."""
    nets = report.get("detailed_net_timings")
    if nets is None:
        raise UserError("the report has no detailed net timings: run nextpnr with --detailed-timing-report "
                        "(make fpga FPGA_ARGS=\"--detailed-timing ...\")")
    late = []
    for net in nets:
        for sink in net.get("endpoints", []):
            t = arrival(sink)
            if t <= period_ns or not is_register_input(sink["cell"], sink["port"]):
                continue
            late.append({"group": group_of(sink["cell"]), "cell": sink["cell"], "port": sink["port"],
                         "driver": net.get("driver", "?"), "ns": round(t, 2)})
    return sorted(late, key=lambda x: (-x["ns"], x["cell"], x["port"]))


def late_groups(report: dict, period_ns: float) -> list[dict]:
    """Register inputs arriving after period_ns, grouped: [{group, unit, count, worst_ns,
    ports}] (ports: late inputs per port kind), the latest group first."""
    groups: dict[str, dict] = {}
    for x in late_inputs(report, period_ns):
        name = x["group"]
        g = groups.setdefault(name, {"group": name, "unit": unit_of_name(name) or "top",
                                     "count": 0, "worst_ns": 0.0, "ports": Counter()})
        g["count"] += 1
        g["worst_ns"] = max(g["worst_ns"], x["ns"])
        g["ports"][port_kind(x["port"])] += 1
    return sorted(groups.values(), key=lambda g: (-g["worst_ns"], g["group"]))


def render(groups: list[dict], period_ns: float, top: int) -> str:
    total = sum(g["count"] for g in groups)
    lines = [f"{len(groups)} registers ({total} inputs) arrive after {period_ns:.3f} ns"]
    for g in groups[:top]:
        ports = ", ".join(f"{k} {n}" for k, n in sorted(g["ports"].items(), key=lambda kv: (-kv[1], kv[0])))
        lines.append(f"{g['worst_ns']:6.2f} ns  {g['count']:4d}  {g['unit']:12s} {g['group']}  ({ports})")
    if len(groups) > top:
        lines.append(f"... {len(groups) - top} more (--top)")
    return "\n".join(lines)


def render_inputs(inputs: list[dict], pattern: str, period_ns: float, top: int) -> str:
    """The late inputs of the groups matching pattern, one per line with its driver."""
    rx = re.compile(pattern)
    sel = [x for x in inputs if rx.search(x["group"])]
    lines = [f"{len(sel)} inputs of groups matching '{pattern}' arrive after {period_ns:.3f} ns"]
    for x in sel[:top]:
        lines.append(f"{x['ns']:6.2f} ns  {x['cell']}.{x['port']}  <- {x['driver']}")
    if len(sel) > top:
        lines.append(f"... {len(sel) - top} more (--top)")
    return "\n".join(lines)


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.endpoints", description=__doc__.splitlines()[0])
    ap.add_argument("report", type=Path, help="nextpnr's JSON report of a run with --detailed-timing-report")
    ap.add_argument("--freq", type=float, default=DEFAULT_FREQ,
                    help=f"clock in MHz whose period is the limit (default {DEFAULT_FREQ:g})")
    ap.add_argument("--top", type=int, default=40, help="groups (or inputs) printed (default 40)")
    ap.add_argument("--inputs", metavar="REGEX",
                    help="list the late inputs of the groups this regex matches, each with its driving cell")
    return ap.parse_args(argv)


def run(args: argparse.Namespace) -> None:
    if not 1.0 <= args.freq <= 1000.0:
        raise UserError(f"--freq: {args.freq:g} MHz is out of range 1..1000")
    if args.top < 0:
        raise UserError(f"--top: {args.top} is negative")
    try:
        report = json.loads(args.report.read_text())
    except OSError as e:
        raise UserError(f"cannot read {args.report}: {e.strerror}") from None
    except ValueError:
        raise UserError(f"{args.report} is not a JSON file") from None
    period = 1000.0 / args.freq
    if args.inputs is not None:
        try:
            re.compile(args.inputs)
        except re.error as e:
            raise UserError(f"--inputs: '{args.inputs}' is not a regular expression: {e}") from None
        print(render_inputs(late_inputs(report, period), args.inputs, period, args.top))
    else:
        print(render(late_groups(report, period), period, args.top))


def main(argv: list[str] | None = None) -> int:
    return cli_main("endpoints", lambda: run(parse_args(argv)))


if __name__ == "__main__":
    raise SystemExit(main())
