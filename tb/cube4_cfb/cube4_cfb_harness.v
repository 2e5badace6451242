`default_nettype none
`include "cube4_defs.vh"
// =============================================================================
// cube4_cfb_harness  (simulation only)
// -----------------------------------------------------------------------------
// Purpose
//   cube4_cfb for tb/cube4_cfb: the host's register ports one by one (packed
//   into the view and address buses as cube4_top packs them) and the tag
//   fields the testbench checks, read from the tag by its layout
//   (cube4_defs.vh), so that the testbench needs no copy of either layout;
//   cube4_stream_check watches the request stream. The rectangle table's
//   fields (RECTS = 1) come one port each, packed as CUBE4_RECT_PACK.
//
// Parameters: as cube4_cfb.   Latency: that of cube4_cfb (no registers here).
// =============================================================================
module cube4_cfb_harness #(
    parameter integer P           = 8,
    parameter integer MAX_DIM     = 256,
    parameter integer ADDR_W      = 16,
    parameter integer WEIGHT_W    = 8,
    parameter integer MAX_SS_LOG2 = 0,
    parameter integer RECTS       = 0,
    parameter integer BEATS       = 0,
    parameter integer RATE        = 2,
    `CUBE4_GEOMETRY,
    `CUBE4_VIEW_LAYOUT,
    `CUBE4_ADDR_LAYOUT,
    `CUBE4_TAG_LAYOUT,
    `CUBE4_RECT_LAYOUT,
    localparam integer BLOCK_LOG2 = 2,
    `CUBE4_STOP_LAYOUT,
    `CUBE4_BLOCK_LAYOUT
) (
    input  wire                  clk,
    input  wire                  rst,
    input  wire                  start,
    output wire                  busy,
    `CUBE4_VIEW_PORTS
    `CUBE4_ADDR_PORTS
    `CUBE4_RECT_PORTS
    input  wire                  rect_we,
    input  wire [M_W-1:0]        rect_addr,
    output wire                  req_valid,
    input  wire                  req_ready,
    output wire [P*ADDR_W-1:0]   req_addr,
    output wire [P-1:0]          req_rden,
    output wire [M_W-1:0]        tag_m,
    output wire [PB_W-1:0]       tag_pb,
    output wire                  tag_emit,
    output wire [DIM_W-1:0]      tag_j,
    output wire                  tag_eop,
    `CUBE4_BEATS_IN_PORTS,
    output wire [4*P-1:0]        req_bits,
    output wire                  req_eos,
    output wire                  req_eoss,
    output wire                  tag_lower_mem,
    output wire                  tag_upper_mem,
    output wire                  tag_bbwe,
    output wire                  tag_uuse,
    output wire                  tag_k0odd
);
    wire [TAG_W-1:0]  tag;
    wire [RECT_W-1:0] rect_data = `CUBE4_RECT_PACK;
    cube4_cfb #(
        .P           (P),
        .MAX_DIM     (MAX_DIM),
        .ADDR_W      (ADDR_W),
        .WEIGHT_W    (WEIGHT_W),
        .MAX_SS_LOG2 (MAX_SS_LOG2),
        .RECTS       (RECTS),
        .BEATS       (BEATS),
        .RATE        (RATE)
    ) u_cfb (
        .clk       (clk),
        .rst       (rst),
        .start     (start),
        .busy      (busy),
        .cfg       (`CUBE4_VIEW_PACK),
        .cfg_addr  (`CUBE4_ADDR_PACK),
        .rect_we   (rect_we),
        .rect_addr (rect_addr),
        .rect_data (rect_data),
        .blk_base  (blk_base),
        .nbr_en    (nbr_en),
        .blk_we    (blk_we),
        .blk_addr  (blk_addr),
        .blk_data  (blk_data),
        .tab_we    (tab_we),
        .tab_addr  (tab_addr),
        .tab_data  (tab_data),
        .rep_valid (rep_valid),
        .rep_j     (rep_j),
        .rep_pb    (rep_pb),
        .rep_stx   (rep_stx),
        .rep_sty   (rep_sty),
        .rep_en    (rep_en),
        .rep_end   (rep_end),
        .com_m     (com_m),
        .req_bits  (req_bits),
        .req_eos   (req_eos),
        .req_eoss  (req_eoss),
        .req_valid (req_valid),
        .req_ready ({`CUBE4_CFB_ADV_N{req_ready}}),   // its copies, one per advance
        .req_addr  (req_addr),
        .req_rden  (req_rden),
        .req_tag   (tag)
    );
    cube4_stream_check #(.NAME ("cfb.req"), .DATA_W (P * ADDR_W + P + TAG_W + 4 * P + 2)) u_chk_req (
        .clk (clk), .rst (rst), .valid (req_valid), .ready (req_ready),
        .data ({req_addr, req_rden, tag, req_bits, req_eos, req_eoss}));
    assign tag_m         = tag[TAG_M +: M_W];
    assign tag_pb        = tag[TAG_PB +: PB_W];
    assign tag_emit      = tag[TAG_EMIT];
    assign tag_j         = tag[TAG_J +: DIM_W];
    assign tag_eop       = tag[TAG_EOP];
    assign tag_lower_mem = tag[TAG_LMEM];
    assign tag_upper_mem = tag[TAG_UMEM];
    assign tag_bbwe      = tag[TAG_BBWE];
    assign tag_uuse      = tag[TAG_UUSE];
    assign tag_k0odd     = tag[TAG_K0ODD];
endmodule
`default_nettype wire
