"""The rectangle table's write port of the harnesses (rect_we, rect_addr and one rt_<field>
port per field of CUBE4_RECT_LAYOUT), driven from cocotb."""

from __future__ import annotations

from cocotb.triggers import RisingEdge

from cube4.memory import rect_table


async def write_rect_table(dut, trav, rects, p: int, addr_w: int) -> None:
    """Write the table of ``rects`` (cube4.memory.rect_table), one entry a clock, then
    leave the port idle."""
    for m, entry in enumerate(rect_table(trav, rects, p, addr_w)):
        for name, val in entry.items():
            getattr(dut, "rt_" + name).value = int(val)
        dut.rect_addr.value = m
        dut.rect_we.value = 1
        await RisingEdge(dut.clk)
    dut.rect_we.value = 0
