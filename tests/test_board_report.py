"""`make board` (sim/cube4_reports/board.py): the pipelines' critical path read from a
nextpnr log, and the report's line for it. Fast: no LiteX, Yosys or nextpnr run."""

from __future__ import annotations

from cube4_reports import board

LOG = """\
Info: Critical path report for clock '$glbnet$crg_ecp5pll1_clkout' (posedge -> posedge):
Info:       type curr  total name
Info:   clk-to-q  1.36  1.36 Source u_cube4.g_dram.u_mem.u_desc.mem.0.0.DOA16
Info:    routing  2.13  3.50 Net u_cube4.g_dram.u_mem.u_desc.mem.0.0_DOA16[1] (6,82) -> (5,42)
Info:                          Sink u_cube4.g_dram.u_mem.o_valid_q_LUT4_B.C
Info:                          Defined in:
Info:                               /somewhere/rtl/cube4_dram_fetch.v:211.5-211.9
Info:      logic  0.15  5.25 Source u_cube4.g_dram.u_mem.o_valid_q_LUT4_B.OFX
Info:    routing  0.60  9.69 Net x (4,44) -> (4,43)
Info:      logic  0.28  9.97 Source u_cube4.g_dram.u_mem.owed_q_TRELLIS_FF_Q_DI_CCU2C_S0$CCU2_COMB0.FCO
Info: 3.12 ns logic, 7.27 ns routing

Info: Critical path report for clock '$glbnet$sys_clk' (posedge -> posedge):
Info:   clk-to-q  0.31  0.31 Source sdram_bankmachine1_source_payload_addr_TRELLIS_FF_Q_10.Q
Info:                               /somewhere/rtl/cube4_other.v:1.1-1.2
Info: 1.00 ns logic, 2.00 ns routing
"""


def test_critical_path_of_one_clock(tmp_path):
    log = tmp_path / "nextpnr.log"
    log.write_text(LOG)
    cp = board.critical_path(log, "ecp5pll1_clkout")
    assert cp["rtl"] == ["rtl/cube4_dram_fetch.v:211"]          # not the next clock's lines
    assert cp["cells"] == ["g_dram.u_mem.u_desc.mem", "g_dram.u_mem.o_valid_q", "g_dram.u_mem.owed_q"]
    assert (cp["logic_ns"], cp["routing_ns"]) == (3.12, 7.27)
    assert board.critical_path(log, "no_such_clock") == {}
    assert board.critical_path(tmp_path / "missing.log", "ecp5pll1_clkout") == {}
    line = board._path_lines({"runs": [{"seed": 1, "critical_path": cp}]})[0]
    assert line.startswith("The pipelines' critical path (seed 1): 3.12 ns logic, 7.27 ns routing, through "
                           "`rtl/cube4_dram_fetch.v:211`, cells named after `g_dram.u_mem.u_desc.mem`")
