// =============================================================================
// cube4_defs.vh -- the one definitions file of the Cube-4 RTL
// -----------------------------------------------------------------------------
// Everything that more than one unit must agree on is defined here once:
//   * the derived widths, as functions of the top parameters
//     (P, MAX_DIM, MAX_SS_LOG2, WEIGHT_W, ADDR_W);
//   * the layout of a voxel memory word (value and voxel gradients);
//   * the layout of the view-register bus (cfg), of the address-register bus
//     (cfg_addr), of the CFB's beat tag (CFB -> memory -> TRI) and of the
//     stream header that travels TRI -> GRA -> SHA -> COM, with named fields;
//   * the lane arithmetic: mod P and the position t a lane holds (eq. 1).
//
// Use
//   `include "cube4_defs.vh" at the top of the file (include directory rtl/).
//   The layouts are localparam lists to be placed in a module's parameter port
//   list after its own parameters, so that ports can use them:
//       module cube4_x #(
//           parameter integer P = 8, parameter integer MAX_DIM = 256,
//           parameter integer MAX_SS_LOG2 = 0,
//           `CUBE4_GEOMETRY
//       ) ( ... input wire [HDR_W-1:0] in_hdr, ... );
//   A list needs the parameters it names in scope:
//       CUBE4_GEOMETRY    P, MAX_DIM, MAX_SS_LOG2
//       CUBE4_VIEW_LAYOUT the above and WEIGHT_W
//       CUBE4_TAG_LAYOUT  the above
//       CUBE4_ADDR_LAYOUT ADDR_W
//       CUBE4_WORD_LAYOUT VOXEL_W, VGRAD
//       CUBE4_GRA_LAYOUT  CUBE4_GEOMETRY
//   `CUBE4_RANGE(...) in a generate region checks a parameter's range.
//   `CUBE4_LANE_FUNCTIONS in a module body (after CUBE4_GEOMETRY) defines the
//   lane functions. `CUBE4_VIEW_FIELDS(bus) in a module body declares one wire
//   cfg_<name> per view register, read from the bus. `CUBE4_VIEW_PORTS and
//   `CUBE4_ADDR_PORTS, on their own lines in a port list before further ports,
//   declare the same registers as input ports (cube4_top and the harnesses);
//   `CUBE4_VIEW_PACK and `CUBE4_ADDR_PACK pack those ports into the buses.
//   Localparams are not overridable: a unit's instantiation sets only the top
//   parameters it names.
//
// Bit growth and rounding: none here (widths and bit positions only).
// =============================================================================
`ifndef CUBE4_DEFS_VH
`define CUBE4_DEFS_VH

// ---------------------------------------------------------------- geometry
//   DIM_W    a dimension 0..MAX_DIM
//   NBMAX    partial beams per beam at most, ceil(MAX_DIM / P)
//   NB_W     a partial-beam count 0..NBMAX;  PB_W  a partial-beam index
//   LANE_W   a lane index or a coordinate mod P
//   M_W      a sample slice index 0..M (M = (MAX_DIM - 1) * S + 1)
//   SB_W     a slot j * NB + pb of a slice (slice buffers)
//   IW       a position pb * P + t + 1 along i
//   HDR_*    the stream header (LSB first):
//              INSIDE [P]   the lane's sample is inside the volume box
//              LVALID [P]   the lane holds a position i < NI (with slice
//                           rectangles: a position its slice traverses)
//              KEEP   [P]   lane valid, inside the window and on the kept side
//                           of the cut plane (cube4_clip); a sample counts when
//                           INSIDE and KEEP (numerics.md section 12)
//              CTRL   [7]   bit 0 X-step, 1 Y-step of slice m; 2 old X-step,
//                           3 old Y-step (slice m - 1); 4 sop; 5 eop;
//                           6 the row is j = NJ - 1
//              SKEW   [LANE_W]  lane alignment of the row (lane_pos)
//              PB     [PB_W], J [DIM_W], M [M_W]   partial beam, row, slice
`define CUBE4_GEOMETRY \
    localparam integer DIM_W  = $clog2(MAX_DIM + 1), \
    localparam integer NBMAX  = (MAX_DIM + P - 1) / P, \
    localparam integer NB_W   = $clog2(NBMAX + 1), \
    localparam integer PB_W   = (NBMAX > 1) ? $clog2(NBMAX) : 1, \
    localparam integer LANE_W = (P > 1) ? $clog2(P) : 1, \
    localparam integer M_W    = $clog2((MAX_DIM - 1) * (1 << MAX_SS_LOG2) + 2), \
    localparam integer SB_W   = $clog2(MAX_DIM * NBMAX), \
    localparam integer IW     = $clog2(MAX_DIM + 2 * P + 1), \
    localparam integer HDR_INSIDE = 0, \
    localparam integer HDR_LVALID = P, \
    localparam integer HDR_KEEP   = 2 * P, \
    localparam integer HDR_CTRL   = 3 * P, \
    localparam integer HDR_SKEW   = 3 * P + 7, \
    localparam integer HDR_PB     = HDR_SKEW + LANE_W, \
    localparam integer HDR_J      = HDR_PB + PB_W, \
    localparam integer HDR_M      = HDR_J + DIM_W, \
    localparam integer HDR_W      = HDR_M + M_W, \
    localparam integer CTRL_SX = 0, \
    localparam integer CTRL_SY = 1, \
    localparam integer CTRL_OSX = 2, \
    localparam integer CTRL_OSY = 3, \
    localparam integer CTRL_SOP = 4, \
    localparam integer CTRL_EOP = 5, \
    localparam integer CTRL_YLAST = 6

// ---------------------------------------------------------------- memory word
// A voxel memory word (golden/cube4/vgrad.py pack_words), LSB first: the voxel
// (VOXEL_W bits); with VGRAD = 1 then the voxel gradient's x, y, z components,
// VG_W = VOXEL_W + 3 bits each in offset binary (g + 2^(VG_W-1)), which TRI
// interpolates like the voxel (numerics.md section 5b); with LABELS = 1 (and
// VGRAD = 0) the voxel's label above it (golden/cube4/labels.py pack_words),
// LABEL_W bits, which TRI picks from the nearest corner (numerics.md section 24).
// Needs VOXEL_W, VGRAD, LABELS.
//   VG_W     a stored gradient component
//   LABEL_W  a label: 0 .. 15
//   LBL_W    the label bits of a word and of a sample: LABEL_W with LABELS, else 0
//   WORD_W   a memory word: VOXEL_W, VOXEL_W + 3 * VG_W, or VOXEL_W + LABEL_W
//   SMP_W    a sample as TRI, GRA and SHA's input carry it: {label, value},
//            VOXEL_W + LBL_W bits (the gradient channels leave at TRI's output)
//   NCH      channels TRI interpolates: 1, or 4
`define CUBE4_WORD_LAYOUT \
    localparam integer VG_W    = VOXEL_W + 3, \
    localparam integer LABEL_W = 4, \
    localparam integer LBL_W   = (LABELS != 0) ? LABEL_W : 0, \
    localparam integer WORD_W  = ((VGRAD != 0) ? VOXEL_W + 3 * VG_W : VOXEL_W) + LBL_W, \
    localparam integer SMP_W   = VOXEL_W + LBL_W, \
    localparam integer NCH     = (VGRAD != 0) ? 4 : 1

// ---------------------------------------------------------------- view registers
// The host's view registers (golden/cube4/memory.py frontend_regs, top_regs),
// stable from start to done, as one bus (LSB first):
//   NI, NJ, NK [DIM_W]   traversal-frame dims;  NB [NB_W] = ceil(NI / P)
//   FLIP_I/J/K [1]       axis traversed backwards;  SS_LOG2 [2] = log2 S
//   VIEW_X/Y [W+1]       slopes Q1.W in [0, 1]
//   J_R0, K_R0 [LANE_W]  start coordinate mod P of axes j, k
//   I_R1, I_RT [LANE_W]  (NI - 1) mod P; block threshold of axis i
//   SX, SY [DIM_W]       stepx(M-1), stepy(M-1) (COM's pixel addresses)
//   MODE [2]             0 composite, 1 X-ray, 2 MIP, 3 MinIP (numerics.md section 13)
//   PH0_X, PH0_Y [PHASE_W]  the template's phase at m = 0, PHASE_W = W + MAX_SS_LOG2
//   WIN_I0, WIN_I1, WIN_J0, WIN_J1 [DIM_W], WIN_M0, WIN_M1 [M_W]
//                        the window: samples with I0 <= i < I1, J0 <= j < J1,
//                        M0 <= m < M1 count (numerics.md section 12)
//   CR_I0, CR_I1, CR_J0, CR_J1 [DIM_W], CR_M0, CR_M1 [M_W], CR_HIDE [27]
//                        crop regions: along i a sample is below (0) when i < CR_I0,
//                        above (2) when i > CR_I1 or i = CR_I1 and wx > 0, else
//                        within (1); j alike with wy; m below when m < CR_M0, above
//                        when m > CR_M1; it counts unless bit ri + 3 rj + 9 rm of
//                        CR_HIDE is set (0: every region counts; numerics.md section 12)
//   CUT_A, CUT_B, CUT_C [CUT_W], CUT_D [CUT_E_W]  the cut plane, signed: a sample
//                        counts when A (i 2^W + wx) + B (j 2^W + wy) + C m + D >= 0
//   CUT_T [CUT_E_W]      the slab's far face (SLAB = 1): a sample counts only when
//                        also E <= CUT_T (2^47 - 1: no slab)
//   FALL_SH [6], FALL_ON [1]  the slab's falloff (SLAB = 1, blending modes): with
//                        FALL_ON the sample's opacity is multiplied by
//                        f = min(min(E, CUT_T - E) >> FALL_SH, 256), FALL_W = 9 bits
//                        (numerics.md section 12, golden/cube4/clip.py)
//   DEPTH_T [25]         depth out (ZOUT = 1): a blending ray passes when its T <=
//                        DEPTH_T (Q0.ACC_W, ACC_W <= 24; numerics.md section 21)
//   FACES [6]            the faces of the frame's box that are the volume's, whose
//                        rays' first and last samples are path-weighted (bits I0, I1,
//                        J0, J1, K0, K1 from bit 0; 0: no weighting; numerics.md
//                        section 17, golden/cube4/pathlen.py)
//   BB_I, BB_J, BB_K [DIM_W]  the beat schedule (BEATS = 1): the frame's i, j, k
//                        axes' bases in the volume, as the block table reads them
//                        (golden/cube4/memory.py beat_regs)
//   NBR [1]              the beat schedule's neighbour term (termination in a GRA frame)
//   TERM [1], TAU [25], VMIN, VMAX [16]   ray termination (BEATS = 1): on; the
//                        composite threshold on T (Q0.ACC_W); the volume's smallest
//                        and largest value (MIP, MinIP; numerics.md section 19)
`define CUBE4_VIEW_LAYOUT \
    localparam integer VIEW_NI      = 0, \
    localparam integer VIEW_NJ      = VIEW_NI + DIM_W, \
    localparam integer VIEW_NK      = VIEW_NJ + DIM_W, \
    localparam integer VIEW_NB      = VIEW_NK + DIM_W, \
    localparam integer VIEW_FLIP_I  = VIEW_NB + NB_W, \
    localparam integer VIEW_FLIP_J  = VIEW_FLIP_I + 1, \
    localparam integer VIEW_FLIP_K  = VIEW_FLIP_J + 1, \
    localparam integer VIEW_SS_LOG2 = VIEW_FLIP_K + 1, \
    localparam integer VIEW_VIEW_X  = VIEW_SS_LOG2 + 2, \
    localparam integer VIEW_VIEW_Y  = VIEW_VIEW_X + WEIGHT_W + 1, \
    localparam integer VIEW_J_R0    = VIEW_VIEW_Y + WEIGHT_W + 1, \
    localparam integer VIEW_K_R0    = VIEW_J_R0 + LANE_W, \
    localparam integer VIEW_I_R1    = VIEW_K_R0 + LANE_W, \
    localparam integer VIEW_I_RT    = VIEW_I_R1 + LANE_W, \
    localparam integer VIEW_SX      = VIEW_I_RT + LANE_W, \
    localparam integer VIEW_SY      = VIEW_SX + DIM_W, \
    localparam integer VIEW_MODE    = VIEW_SY + DIM_W, \
    localparam integer PHASE_W      = WEIGHT_W + MAX_SS_LOG2, \
    localparam integer VIEW_PH0_X   = VIEW_MODE + 2, \
    localparam integer VIEW_PH0_Y   = VIEW_PH0_X + PHASE_W, \
    localparam integer VIEW_WIN_I0  = VIEW_PH0_Y + PHASE_W, \
    localparam integer VIEW_WIN_I1  = VIEW_WIN_I0 + DIM_W, \
    localparam integer VIEW_WIN_J0  = VIEW_WIN_I1 + DIM_W, \
    localparam integer VIEW_WIN_J1  = VIEW_WIN_J0 + DIM_W, \
    localparam integer VIEW_WIN_M0  = VIEW_WIN_J1 + DIM_W, \
    localparam integer VIEW_WIN_M1  = VIEW_WIN_M0 + M_W, \
    localparam integer VIEW_CR_I0   = VIEW_WIN_M1 + M_W, \
    localparam integer VIEW_CR_I1   = VIEW_CR_I0 + DIM_W, \
    localparam integer VIEW_CR_J0   = VIEW_CR_I1 + DIM_W, \
    localparam integer VIEW_CR_J1   = VIEW_CR_J0 + DIM_W, \
    localparam integer VIEW_CR_M0   = VIEW_CR_J1 + DIM_W, \
    localparam integer VIEW_CR_M1   = VIEW_CR_M0 + M_W, \
    localparam integer VIEW_CR_HIDE = VIEW_CR_M1 + M_W, \
    localparam integer CUT_W        = 18, \
    localparam integer CUT_E_W      = 48, \
    localparam integer VIEW_CUT_A   = VIEW_CR_HIDE + 27, \
    localparam integer VIEW_CUT_B   = VIEW_CUT_A + CUT_W, \
    localparam integer VIEW_CUT_C   = VIEW_CUT_B + CUT_W, \
    localparam integer VIEW_CUT_D   = VIEW_CUT_C + CUT_W, \
    localparam integer VIEW_CUT_T   = VIEW_CUT_D + CUT_E_W, \
    localparam integer VIEW_FALL_SH = VIEW_CUT_T + CUT_E_W, \
    localparam integer VIEW_FALL_ON = VIEW_FALL_SH + 6, \
    localparam integer FALL_W       = 9, \
    localparam integer VIEW_DEPTH_T = VIEW_FALL_ON + 1, \
    localparam integer VIEW_FACES   = VIEW_DEPTH_T + 25, \
    localparam integer VIEW_BB_I    = VIEW_FACES + 6, \
    localparam integer VIEW_BB_J    = VIEW_BB_I + DIM_W, \
    localparam integer VIEW_BB_K    = VIEW_BB_J + DIM_W, \
    localparam integer VIEW_NBR     = VIEW_BB_K + DIM_W, \
    localparam integer VIEW_TERM    = VIEW_NBR + 1, \
    localparam integer VIEW_TAU     = VIEW_TERM + 1, \
    localparam integer VIEW_VMIN    = VIEW_TAU + 25, \
    localparam integer VIEW_VMAX    = VIEW_VMIN + 16, \
    localparam integer VIEW_W       = VIEW_VMAX + 16

// The view bus from the individual register ports (cube4_top and the harnesses).
`define CUBE4_VIEW_PACK {cfg_vmax, cfg_vmin, cfg_tau, cfg_term, cfg_nbr, cfg_bb_k, cfg_bb_j, cfg_bb_i, \
    cfg_faces, cfg_depth_t, cfg_fall_on, cfg_fall_sh, cfg_cut_t, cfg_cut_d, cfg_cut_c, cfg_cut_b, cfg_cut_a, \
    cfg_cr_hide, cfg_cr_m1, cfg_cr_m0, cfg_cr_j1, cfg_cr_j0, cfg_cr_i1, cfg_cr_i0, \
    cfg_win_m1, cfg_win_m0, cfg_win_j1, cfg_win_j0, cfg_win_i1, cfg_win_i0, \
    cfg_ph0_y, cfg_ph0_x, cfg_mode, cfg_sy, cfg_sx, cfg_i_rt, cfg_i_r1, cfg_k_r0, cfg_j_r0, \
    cfg_view_y, cfg_view_x, cfg_ss_log2, cfg_flip_k, cfg_flip_j, cfg_flip_i, \
    cfg_nb, cfg_nk, cfg_nj, cfg_ni}

// The view registers as input ports, one per field of CUBE4_VIEW_LAYOUT (cube4_top
// and the harnesses; CUBE4_VIEW_PACK packs them into the bus). Each declaration ends
// with a comma: the macro stands on its own line before further ports.
`define CUBE4_VIEW_PORTS \
    input  wire [DIM_W-1:0]   cfg_ni, \
    input  wire [DIM_W-1:0]   cfg_nj, \
    input  wire [DIM_W-1:0]   cfg_nk, \
    input  wire [NB_W-1:0]    cfg_nb, \
    input  wire               cfg_flip_i, \
    input  wire               cfg_flip_j, \
    input  wire               cfg_flip_k, \
    input  wire [1:0]         cfg_ss_log2, \
    input  wire [WEIGHT_W:0]  cfg_view_x, \
    input  wire [WEIGHT_W:0]  cfg_view_y, \
    input  wire [LANE_W-1:0]  cfg_j_r0, \
    input  wire [LANE_W-1:0]  cfg_k_r0, \
    input  wire [LANE_W-1:0]  cfg_i_r1, \
    input  wire [LANE_W-1:0]  cfg_i_rt, \
    input  wire [DIM_W-1:0]   cfg_sx, \
    input  wire [DIM_W-1:0]   cfg_sy, \
    input  wire [1:0]         cfg_mode, \
    input  wire [PHASE_W-1:0] cfg_ph0_x, \
    input  wire [PHASE_W-1:0] cfg_ph0_y, \
    input  wire [DIM_W-1:0]   cfg_win_i0, \
    input  wire [DIM_W-1:0]   cfg_win_i1, \
    input  wire [DIM_W-1:0]   cfg_win_j0, \
    input  wire [DIM_W-1:0]   cfg_win_j1, \
    input  wire [M_W-1:0]     cfg_win_m0, \
    input  wire [M_W-1:0]     cfg_win_m1, \
    input  wire [DIM_W-1:0]   cfg_cr_i0, \
    input  wire [DIM_W-1:0]   cfg_cr_i1, \
    input  wire [DIM_W-1:0]   cfg_cr_j0, \
    input  wire [DIM_W-1:0]   cfg_cr_j1, \
    input  wire [M_W-1:0]     cfg_cr_m0, \
    input  wire [M_W-1:0]     cfg_cr_m1, \
    input  wire [26:0]        cfg_cr_hide, \
    input  wire [CUT_W-1:0]   cfg_cut_a, \
    input  wire [CUT_W-1:0]   cfg_cut_b, \
    input  wire [CUT_W-1:0]   cfg_cut_c, \
    input  wire [CUT_E_W-1:0] cfg_cut_d, \
    input  wire [CUT_E_W-1:0] cfg_cut_t, \
    input  wire [5:0]         cfg_fall_sh, \
    input  wire               cfg_fall_on, \
    input  wire [24:0]        cfg_depth_t, \
    input  wire [5:0]         cfg_faces, \
    input  wire [DIM_W-1:0]   cfg_bb_i, \
    input  wire [DIM_W-1:0]   cfg_bb_j, \
    input  wire [DIM_W-1:0]   cfg_bb_k, \
    input  wire               cfg_nbr, \
    input  wire               cfg_term, \
    input  wire [24:0]        cfg_tau, \
    input  wire [15:0]        cfg_vmin, \
    input  wire [15:0]        cfg_vmax,

// One wire per view register, read from a view bus (module body).
`define CUBE4_VIEW_FIELDS(bus) \
    wire [DIM_W-1:0]    cfg_ni      = bus[VIEW_NI +: DIM_W]; \
    wire [DIM_W-1:0]    cfg_nj      = bus[VIEW_NJ +: DIM_W]; \
    wire [DIM_W-1:0]    cfg_nk      = bus[VIEW_NK +: DIM_W]; \
    wire [NB_W-1:0]     cfg_nb      = bus[VIEW_NB +: NB_W]; \
    wire                cfg_flip_i  = bus[VIEW_FLIP_I]; \
    wire                cfg_flip_j  = bus[VIEW_FLIP_J]; \
    wire                cfg_flip_k  = bus[VIEW_FLIP_K]; \
    wire [1:0]          cfg_ss_log2 = bus[VIEW_SS_LOG2 +: 2]; \
    wire [WEIGHT_W:0]   cfg_view_x  = bus[VIEW_VIEW_X +: WEIGHT_W + 1]; \
    wire [WEIGHT_W:0]   cfg_view_y  = bus[VIEW_VIEW_Y +: WEIGHT_W + 1]; \
    wire [LANE_W-1:0]   cfg_j_r0    = bus[VIEW_J_R0 +: LANE_W]; \
    wire [LANE_W-1:0]   cfg_k_r0    = bus[VIEW_K_R0 +: LANE_W]; \
    wire [LANE_W-1:0]   cfg_i_r1    = bus[VIEW_I_R1 +: LANE_W]; \
    wire [LANE_W-1:0]   cfg_i_rt    = bus[VIEW_I_RT +: LANE_W]; \
    wire [DIM_W-1:0]    cfg_sx      = bus[VIEW_SX +: DIM_W]; \
    wire [DIM_W-1:0]    cfg_sy      = bus[VIEW_SY +: DIM_W]; \
    wire [1:0]          cfg_mode    = bus[VIEW_MODE +: 2]; \
    wire [PHASE_W-1:0]  cfg_ph0_x   = bus[VIEW_PH0_X +: PHASE_W]; \
    wire [PHASE_W-1:0]  cfg_ph0_y   = bus[VIEW_PH0_Y +: PHASE_W]; \
    wire [DIM_W-1:0]    cfg_win_i0  = bus[VIEW_WIN_I0 +: DIM_W]; \
    wire [DIM_W-1:0]    cfg_win_i1  = bus[VIEW_WIN_I1 +: DIM_W]; \
    wire [DIM_W-1:0]    cfg_win_j0  = bus[VIEW_WIN_J0 +: DIM_W]; \
    wire [DIM_W-1:0]    cfg_win_j1  = bus[VIEW_WIN_J1 +: DIM_W]; \
    wire [M_W-1:0]      cfg_win_m0  = bus[VIEW_WIN_M0 +: M_W]; \
    wire [M_W-1:0]      cfg_win_m1  = bus[VIEW_WIN_M1 +: M_W]; \
    wire [DIM_W-1:0]    cfg_cr_i0   = bus[VIEW_CR_I0 +: DIM_W]; \
    wire [DIM_W-1:0]    cfg_cr_i1   = bus[VIEW_CR_I1 +: DIM_W]; \
    wire [DIM_W-1:0]    cfg_cr_j0   = bus[VIEW_CR_J0 +: DIM_W]; \
    wire [DIM_W-1:0]    cfg_cr_j1   = bus[VIEW_CR_J1 +: DIM_W]; \
    wire [M_W-1:0]      cfg_cr_m0   = bus[VIEW_CR_M0 +: M_W]; \
    wire [M_W-1:0]      cfg_cr_m1   = bus[VIEW_CR_M1 +: M_W]; \
    wire [26:0]         cfg_cr_hide = bus[VIEW_CR_HIDE +: 27]; \
    wire signed [CUT_W-1:0]   cfg_cut_a = bus[VIEW_CUT_A +: CUT_W]; \
    wire signed [CUT_W-1:0]   cfg_cut_b = bus[VIEW_CUT_B +: CUT_W]; \
    wire signed [CUT_W-1:0]   cfg_cut_c = bus[VIEW_CUT_C +: CUT_W]; \
    wire signed [CUT_E_W-1:0] cfg_cut_d = bus[VIEW_CUT_D +: CUT_E_W]; \
    wire signed [CUT_E_W-1:0] cfg_cut_t = bus[VIEW_CUT_T +: CUT_E_W]; \
    wire [5:0]          cfg_fall_sh = bus[VIEW_FALL_SH +: 6]; \
    wire                cfg_fall_on = bus[VIEW_FALL_ON]; \
    wire [24:0]         cfg_depth_t = bus[VIEW_DEPTH_T +: 25]; \
    wire [5:0]          cfg_faces   = bus[VIEW_FACES +: 6]; \
    wire [DIM_W-1:0]    cfg_bb_i    = bus[VIEW_BB_I +: DIM_W]; \
    wire [DIM_W-1:0]    cfg_bb_j    = bus[VIEW_BB_J +: DIM_W]; \
    wire [DIM_W-1:0]    cfg_bb_k    = bus[VIEW_BB_K +: DIM_W]; \
    wire                cfg_nbr     = bus[VIEW_NBR]; \
    wire                cfg_term    = bus[VIEW_TERM]; \
    wire [24:0]         cfg_tau     = bus[VIEW_TAU +: 25]; \
    wire [15:0]         cfg_vmin    = bus[VIEW_VMIN +: 16]; \
    wire [15:0]         cfg_vmax    = bus[VIEW_VMAX +: 16]

// ---------------------------------------------------------------- address registers
// The address unit's start values and strides (golden/cube4/memory.py), ADDR_W
// bits each, as one bus (LSB first): J_A0, J_LIN, J_BLK, K_A0, K_LIN, K_BLK,
// I_A0, I_PB, I_LIN.
`define CUBE4_ADDR_LAYOUT \
    localparam integer ADR_J_A0  = 0 * ADDR_W, \
    localparam integer ADR_J_LIN = 1 * ADDR_W, \
    localparam integer ADR_J_BLK = 2 * ADDR_W, \
    localparam integer ADR_K_A0  = 3 * ADDR_W, \
    localparam integer ADR_K_LIN = 4 * ADDR_W, \
    localparam integer ADR_K_BLK = 5 * ADDR_W, \
    localparam integer ADR_I_A0  = 6 * ADDR_W, \
    localparam integer ADR_I_PB  = 7 * ADDR_W, \
    localparam integer ADR_I_LIN = 8 * ADDR_W, \
    localparam integer ADR_W_ALL = 9 * ADDR_W

`define CUBE4_ADDR_PACK {cfg_i_lin, cfg_i_pb, cfg_i_a0, cfg_k_blk, cfg_k_lin, cfg_k_a0, \
    cfg_j_blk, cfg_j_lin, cfg_j_a0}

// The address registers as input ports, as CUBE4_VIEW_PORTS (CUBE4_ADDR_PACK).
`define CUBE4_ADDR_PORTS \
    input  wire [ADDR_W-1:0] cfg_j_a0, \
    input  wire [ADDR_W-1:0] cfg_j_lin, \
    input  wire [ADDR_W-1:0] cfg_j_blk, \
    input  wire [ADDR_W-1:0] cfg_k_a0, \
    input  wire [ADDR_W-1:0] cfg_k_lin, \
    input  wire [ADDR_W-1:0] cfg_k_blk, \
    input  wire [ADDR_W-1:0] cfg_i_a0, \
    input  wire [ADDR_W-1:0] cfg_i_pb, \
    input  wire [ADDR_W-1:0] cfg_i_lin,

// ---------------------------------------------------------------- CFB beat tag
// Travels with a memory read beat, unchanged, from cube4_cfb through the
// memory to cube4_tri (LSB first):
//   STEPS [4]   {old Y, old X, Y, X} steps of the emitted row's slice
//   YLAST       the emitted row is j = NJ - 1
//   SKEW [LANE_W], J [DIM_W], M [M_W]   the emitted row (as the header)
//   WZ, WY, WX [W]   resampling weights of the emitted row (Q0.W)
//   PB [PB_W]   partial beam (beam-buffer slot);  SB [SB_W] slice-buffer slot
//   K0ODD       slice-buffer parity of the lower slice
//   UUSE        upper slice used (r > 0);  UMEM / LMEM  upper / lower slice
//               comes from memory
//   BBWE        write the beam buffers;  YWRAP  the current row is zero
//   EOP, SOP    last / first sample beat of the frame;  EMIT  beat emits a row
//   LWRAP [P]   lane holds t = P - 1 (beam extension)
//   LNBR [P]    lane's position + 1 < NI;  LVAL [P]  lane's position < NI
//   LINL [P]    lane's sample is not below the low sides of its slice's
//               rectangle (i >= I_IN and j >= J_IN; slice rectangles, RECTS =
//               1 of cube4_cfb); all ones otherwise
`define CUBE4_TAG_LAYOUT \
    localparam integer TAG_STEPS = 0, \
    localparam integer TAG_YLAST = 4, \
    localparam integer TAG_SKEW  = 5, \
    localparam integer TAG_J     = TAG_SKEW + LANE_W, \
    localparam integer TAG_M     = TAG_J + DIM_W, \
    localparam integer TAG_WZ    = TAG_M + M_W, \
    localparam integer TAG_WY    = TAG_WZ + WEIGHT_W, \
    localparam integer TAG_WX    = TAG_WY + WEIGHT_W, \
    localparam integer TAG_PB    = TAG_WX + WEIGHT_W, \
    localparam integer TAG_SB    = TAG_PB + PB_W, \
    localparam integer TAG_K0ODD = TAG_SB + SB_W, \
    localparam integer TAG_UUSE  = TAG_K0ODD + 1, \
    localparam integer TAG_UMEM  = TAG_UUSE + 1, \
    localparam integer TAG_LMEM  = TAG_UMEM + 1, \
    localparam integer TAG_BBWE  = TAG_LMEM + 1, \
    localparam integer TAG_YWRAP = TAG_BBWE + 1, \
    localparam integer TAG_EOP   = TAG_YWRAP + 1, \
    localparam integer TAG_SOP   = TAG_EOP + 1, \
    localparam integer TAG_EMIT  = TAG_SOP + 1, \
    localparam integer TAG_LWRAP = TAG_EMIT + 1, \
    localparam integer TAG_LNBR  = TAG_LWRAP + P, \
    localparam integer TAG_LVAL  = TAG_LNBR + P, \
    localparam integer TAG_LINL  = TAG_LVAL + P, \
    localparam integer TAG_W     = TAG_LINL + P

// ---------------------------------------------------------------- stop table
// Depth in (ZIN = 1, cube4_com_stop; golden/cube4/memory.py stop_table): the
// stop slices of the base plane's pixels (by, bx) in P banks, bank bx mod P,
// word {by [ROWS_W], bx div P [COLS_W]}; a base plane has at most 2 MAX_DIM - 1
// rows and columns (NI + SX, NJ + SY).
//   ROWS_W = clog2(2 MAX_DIM), COLS_W = clog2(ceil(2 MAX_DIM / P)) (at least 1),
//   STOP_AW = ROWS_W + COLS_W
`define CUBE4_STOP_LAYOUT \
    localparam integer ROWS_W  = $clog2(2 * MAX_DIM), \
    localparam integer COLS_W  = ((2 * MAX_DIM + P - 1) / P > 1) ? $clog2((2 * MAX_DIM + P - 1) / P) : 1, \
    localparam integer STOP_AW = ROWS_W + COLS_W

// ---------------------------------------------------------------- the beat schedule's front end
// The decisions' inputs (cube4_cfb_decide; cube4_cfb_skip passes them on): the frame, its
// axes in the volume, the slices' steps, the block table, the ray table's host port and
// COM's reports (the ports are described in cube4_cfb_decide's header). Needs the
// geometry, CUBE4_STOP_LAYOUT and NBK, BK_W (the block table: CUBE4_BLOCK_LAYOUT).
`define CUBE4_BLOCK_LAYOUT \
    localparam integer NBK  = (MAX_DIM + (1 << BLOCK_LOG2) - 1) >> BLOCK_LOG2, \
    localparam integer BK_W = (NBK > 1) ? $clog2(NBK) : 1
`define CUBE4_DECIDE_IN_PORTS \
    input  wire start, output wire busy, \
    input  wire [DIM_W-1:0] ni, input wire [DIM_W-1:0] nj, input wire [NB_W-1:0] nb, input wire [M_W-1:0] nm, \
    input  wire [1:0] ss_log2, \
    input  wire [DIM_W-1:0] sx, input wire [DIM_W-1:0] sy, \
    input  wire [DIM_W-1:0] bi_base, input wire bi_flip, \
    input  wire [DIM_W-1:0] bj_base, input wire bj_flip, \
    input  wire [DIM_W-1:0] bk_base, input wire bk_flip, \
    input  wire st_valid, output wire st_ready, input wire [DIM_W-1:0] st_x, input wire [DIM_W-1:0] st_y, \
    input  wire blk_we, input wire [2*BK_W-1:0] blk_addr, input wire [NBK-1:0] blk_data, \
    input  wire tab_we, input wire [STOP_AW-1:0] tab_addr, input wire [P*M_W-1:0] tab_data, \
    input  wire rep_valid, input wire [DIM_W-1:0] rep_j, input wire [PB_W-1:0] rep_pb, \
    input  wire [DIM_W-1:0] rep_stx, input wire [DIM_W-1:0] rep_sty, \
    input  wire [P-1:0] rep_en, input wire [P*M_W-1:0] rep_end, \
    input  wire [M_W-1:0] com_m

// The beat schedule's inputs of cube4_cfb and cube4_frontend (BEATS = 1; unused
// otherwise): the decisions' inputs past those cube4_cfb derives from the view
// registers (cube4_cfb_decide's header): the frame's axes' bases in the volume {k, j,
// i}, the neighbour term, the block table's and the ray table's host ports, COM's
// reports and its slice count. Needs the geometry, CUBE4_STOP_LAYOUT and
// CUBE4_BLOCK_LAYOUT. No trailing comma.
`define CUBE4_BEATS_IN_PORTS \
    input  wire [3*DIM_W-1:0] blk_base, input wire nbr_en, \
    input  wire blk_we, input wire [2*BK_W-1:0] blk_addr, input wire [NBK-1:0] blk_data, \
    input  wire tab_we, input wire [STOP_AW-1:0] tab_addr, input wire [P*M_W-1:0] tab_data, \
    input  wire rep_valid, input wire [DIM_W-1:0] rep_j, input wire [PB_W-1:0] rep_pb, \
    input  wire [DIM_W-1:0] rep_stx, input wire [DIM_W-1:0] rep_sty, \
    input  wire [P-1:0] rep_en, input wire [P*M_W-1:0] rep_end, \
    input  wire [M_W-1:0] com_m
// COM's reports into the front end's ray table, connected by name to the wires
// com_rep_* of cube4_top (the same bus on cube4_com's outputs and cube4_cfb's inputs)
`define CUBE4_REPORT_CONN \
    .rep_valid(com_rep_valid), .rep_j(com_rep_j), .rep_pb(com_rep_pb), .rep_stx(com_rep_stx), \
    .rep_sty(com_rep_sty), .rep_en(com_rep_en), .rep_end(com_rep_end)
// ... tied off where no beat schedule runs
`define CUBE4_BEATS_IN_NONE \
    .blk_base('0), .nbr_en(1'b0), .blk_we(1'b0), .blk_addr('0), .blk_data('0), \
    .tab_we(1'b0), .tab_addr('0), .tab_data('0), .rep_valid(1'b0), .rep_j('0), \
    .rep_pb('0), .rep_stx('0), .rep_sty('0), .rep_en('0), .rep_end('0), .com_m('0)
// ... and passed on by name
`define CUBE4_BEATS_IN_PASS \
    .blk_base(blk_base), .nbr_en(nbr_en), .blk_we(blk_we), .blk_addr(blk_addr), .blk_data(blk_data), \
    .tab_we(tab_we), .tab_addr(tab_addr), .tab_data(tab_data), .rep_valid(rep_valid), .rep_j(rep_j), \
    .rep_pb(rep_pb), .rep_stx(rep_stx), .rep_sty(rep_sty), .rep_en(rep_en), .rep_end(rep_end), \
    .com_m(com_m)

// ---------------------------------------------------------------- slice rectangles
// One entry per sample slice of the rectangle table of cube4_cfb (RECTS = 1;
// golden/cube4/slices.py, memory.py rect_table; numerics.md section 18), LSB
// first; needs the geometry and ADDR_W:
//   EMPTY       the slice traverses nothing
//   FLUSH       a flush beam emits its last row (the next slice walks other
//               partial beams, or none)
//   LAST        the frame's last slice that is not empty: its flush beam ends
//               the frame (the empty slices after it are not walked)
//   J0, JL [DIM_W]    first and last row traversed;  J_IN [DIM_W] first row inside
//   PB0, PBL [PB_W]   first and last partial beam
//   I_LO, I_IN, I_HI [DIM_W]  positions traversed I_LO <= i < I_HI; inside from I_IN
//   AJ0 [ADDR_W], RJ0 [LANE_W]  A_j and c_j mod P of row J0
//   PBX0 [ADDR_W]     the partial-beam address term of PB0 (I_A0 - PB0 I_PB, or PB0 I_PB)
//   PBP0 [IW]         PB0 * P
//   SB0 [SB_W]        slot J0 * NB + PB0;  SBROW [SB_W]  slot step from a row's
//                     last partial beam to the next row's first, NB - (PBL - PB0)
//   TJ0, TJL [DIM_W]  the rows that hold samples (the traversed rectangle's):
//                     rows J0 .. JL outside them are walked for GRA (slices.py
//                     SliceRects.walk) with no read and no lane valid; JL may be
//                     NJ (a row past the last, for GRA's last centres)
//   (cube4_com) INS   the slice has an inside rectangle: J_IN .. J_HI,
//                     I_IN .. I_HIN [DIM_W] (slices.py SliceRects.inside, the
//                     high sides less a row / column where wy / wx > 0);
//                     STX, STY [DIM_W]  stepx(m), stepy(m)
`define CUBE4_RECT_LAYOUT \
    localparam integer RT_EMPTY = 0, \
    localparam integer RT_FLUSH = 1, \
    localparam integer RT_LAST  = 2, \
    localparam integer RT_J0    = 3, \
    localparam integer RT_JL    = RT_J0 + DIM_W, \
    localparam integer RT_JIN   = RT_JL + DIM_W, \
    localparam integer RT_PB0   = RT_JIN + DIM_W, \
    localparam integer RT_PBL   = RT_PB0 + PB_W, \
    localparam integer RT_ILO   = RT_PBL + PB_W, \
    localparam integer RT_IIN   = RT_ILO + DIM_W, \
    localparam integer RT_IHI   = RT_IIN + DIM_W, \
    localparam integer RT_AJ0   = RT_IHI + DIM_W, \
    localparam integer RT_RJ0   = RT_AJ0 + ADDR_W, \
    localparam integer RT_PBX0  = RT_RJ0 + LANE_W, \
    localparam integer RT_PBP0  = RT_PBX0 + ADDR_W, \
    localparam integer RT_SB0   = RT_PBP0 + IW, \
    localparam integer RT_SBROW = RT_SB0 + SB_W, \
    localparam integer RT_TJ0   = RT_SBROW + SB_W, \
    localparam integer RT_TJL   = RT_TJ0 + DIM_W, \
    localparam integer RT_JHI   = RT_TJL + DIM_W, \
    localparam integer RT_IHIN  = RT_JHI + DIM_W, \
    localparam integer RT_STX   = RT_IHIN + DIM_W, \
    localparam integer RT_STY   = RT_STX + DIM_W, \
    localparam integer RT_INS   = RT_STY + DIM_W, \
    localparam integer RECT_W   = RT_INS + 1

// The table entry from one port per field (the harnesses), as CUBE4_VIEW_PORTS.
`define CUBE4_RECT_PACK {rt_ins, rt_sty, rt_stx, rt_i_hin, rt_j_hi, rt_tjl, rt_tj0, rt_sbrow, rt_sb0, rt_pbp0, rt_pbx0, rt_rj0, rt_aj0, rt_i_hi, rt_i_in, \
    rt_i_lo, rt_pbl, rt_pb0, rt_j_in, rt_jl, rt_j0, rt_last, rt_flush, rt_empty}
`define CUBE4_RECT_PORTS \
    input  wire               rt_empty, \
    input  wire               rt_flush, \
    input  wire               rt_last, \
    input  wire [DIM_W-1:0]   rt_j0, \
    input  wire [DIM_W-1:0]   rt_jl, \
    input  wire [DIM_W-1:0]   rt_j_in, \
    input  wire [PB_W-1:0]    rt_pb0, \
    input  wire [PB_W-1:0]    rt_pbl, \
    input  wire [DIM_W-1:0]   rt_i_lo, \
    input  wire [DIM_W-1:0]   rt_i_in, \
    input  wire [DIM_W-1:0]   rt_i_hi, \
    input  wire [ADDR_W-1:0]  rt_aj0, \
    input  wire [LANE_W-1:0]  rt_rj0, \
    input  wire [ADDR_W-1:0]  rt_pbx0, \
    input  wire [IW-1:0]      rt_pbp0, \
    input  wire [SB_W-1:0]    rt_sb0, \
    input  wire [SB_W-1:0]    rt_sbrow, \
    input  wire [DIM_W-1:0]   rt_tj0, \
    input  wire [DIM_W-1:0]   rt_tjl, \
    input  wire [DIM_W-1:0]   rt_j_hi, \
    input  wire [DIM_W-1:0]   rt_i_hin, \
    input  wire [DIM_W-1:0]   rt_stx, \
    input  wire [DIM_W-1:0]   rt_sty, \
    input  wire               rt_ins,

// ---------------------------------------------------------------- GRA's neighbourhood
// Between GRA's neighbourhood source (cube4_gra_lines, or cube4_gra_walk with
// slice rectangles) and its window (cube4_gra_window). Needs CUBE4_GEOMETRY.
//   GRA_STEPS    copies of the output FIFO's credit, one per group of step
//                registers: copy GRA_STEPS-1 the window and counters (every
//                source's step); copies 0 .. 5 the six delay lines
//                (cube4_gra_lines), or the beat walk's GRA_POS_G groups
//   GRA_POS_G    groups of cube4_gra_pos's registers, each with its own copy
//                of the read, load and step enables (plane A; plane B; the
//                beam buffer's X, P1 with its meta, C, P2b1: 6); the beat
//                walk forms them from credit copies 0 .. GRA_POS_G-1, which
//                only the delay lines use otherwise
//   GRA_META_W   a beat's {real, header}: real = a sample beat of the frame
//   GRA_NSEL     the centre's select flags per lane, bits GSEL_*: the voxel
//                slice changes m -> m+1 (DKF) / m-1 -> m (DKB), the centre is
//                in row 0 (JFIRST) / slice 0 (MFIRST) / row NJ - 1 (YLAST),
//                the Y-step (DYF) and old Y-step (DYB) of its slice
`define CUBE4_GRA_LAYOUT \
    localparam integer GRA_STEPS   = 7, \
    localparam integer GRA_POS_G   = 6, \
    localparam integer GRA_META_W  = 1 + HDR_W, \
    localparam integer GRA_NSEL    = 7, \
    localparam integer GSEL_DYB    = 0, \
    localparam integer GSEL_DYF    = 1, \
    localparam integer GSEL_YLAST  = 2, \
    localparam integer GSEL_MFIRST = 3, \
    localparam integer GSEL_JFIRST = 4, \
    localparam integer GSEL_DKB    = 5, \
    localparam integer GSEL_DKF    = 6

// ---------------------------------------------------------------- unit parameter lists
// The parameter lists several modules share, with the top's defaults (the
// ranges: cube4_top, and for a unit its block's top, document them):
//   CUBE4_SLICE_PARAMS  P, MAX_DIM, WEIGHT_W, MAX_SS_LOG2, CUBE4_GEOMETRY and
//                       CUBE4_VIEW_LAYOUT: a unit that follows the slice walk
//   CUBE4_GRA_PARAMS    CUBE4_SLICE_PARAMS, VOXEL_W and CUBE4_GRA_LAYOUT: GRA's units
//   CUBE4_BUILD_PARAMS  the build's parameters (widths and options, the full
//                       build's defaults; golden/cube4/builds.py is their
//                       definition and a test holds this list to it),
//                       CUBE4_GEOMETRY and CUBE4_VIEW_LAYOUT: the blocks
//                       (cube4_top, cube4_frontend, cube4_sha, cube4_com) take
//                       the whole set and use what they need; CUBE4_BUILD_PASS
//                       passes it on to a block by name
`define CUBE4_BUILD_PARAMS \
    parameter integer P        = 8,  parameter integer MAX_DIM     = 256, \
    parameter integer VOXEL_W  = 8,  parameter integer MAX_SS_LOG2 = 0, \
    parameter integer WEIGHT_W = 8,  parameter integer RMAP_BITS   = 5, \
    parameter integer ALPHA_W  = 12, parameter integer ACC_W       = 16, \
    parameter integer ADDR_W   = 16, \
    parameter integer SHADING  = 1,  parameter integer COMPOSITING = 1, \
    parameter integer EXTREMUM = 1,  parameter integer CLIP        = 1, \
    parameter integer VGRAD    = 0,  parameter integer PLW         = 1, \
    parameter integer RECTS    = 0,  parameter integer SLAB        = 0, \
    parameter integer ZOUT     = 0,  parameter integer ZIN         = 0, \
    parameter integer GMOD     = 0,  parameter integer LABELS      = 0, \
    parameter integer BEATS    = 0, \
    `CUBE4_GEOMETRY, `CUBE4_VIEW_LAYOUT

`define CUBE4_BUILD_PASS \
    .P(P), .MAX_DIM(MAX_DIM), .VOXEL_W(VOXEL_W), .MAX_SS_LOG2(MAX_SS_LOG2), \
    .WEIGHT_W(WEIGHT_W), .RMAP_BITS(RMAP_BITS), .ALPHA_W(ALPHA_W), .ACC_W(ACC_W), \
    .ADDR_W(ADDR_W), .SHADING(SHADING), .COMPOSITING(COMPOSITING), .EXTREMUM(EXTREMUM), \
    .CLIP(CLIP), .VGRAD(VGRAD), .PLW(PLW), .RECTS(RECTS), .SLAB(SLAB), .ZOUT(ZOUT), \
    .ZIN(ZIN), .GMOD(GMOD), .LABELS(LABELS), .BEATS(BEATS)

`define CUBE4_SLICE_PARAMS \
    parameter integer P        = 8, parameter integer MAX_DIM     = 256, \
    parameter integer WEIGHT_W = 8, parameter integer MAX_SS_LOG2 = 0, \
    `CUBE4_GEOMETRY, `CUBE4_VIEW_LAYOUT

`define CUBE4_GRA_PARAMS \
    `CUBE4_SLICE_PARAMS, parameter integer VOXEL_W = 8, `CUBE4_GRA_LAYOUT

// CUBE4_SLICE_PASS, CUBE4_GRA_PASS: pass CUBE4_SLICE_PARAMS's (CUBE4_GRA_PARAMS's)
// build parameters on to a unit by name (its geometry and layouts it derives itself).
`define CUBE4_SLICE_PASS .P(P), .MAX_DIM(MAX_DIM), .WEIGHT_W(WEIGHT_W), .MAX_SS_LOG2(MAX_SS_LOG2)
`define CUBE4_GRA_PASS `CUBE4_SLICE_PASS, .VOXEL_W(VOXEL_W)

// ---------------------------------------------------------------- phases
// A template phase is PHASE_W = W + MAX_SS_LOG2 bits (Q.W+g of a voxel); one
// slice on it adds VIEW (Q1.W, 0 .. 2^W) and wraps at one = 2^(W + g):
//   phase_one(g)                 = 2^(W + g), g = log2(S) (cfg_ss_log2)
//   phase_advance(ph, view, one) = {carry, (ph + view) mod one}, the carry
//   being the slice's step. Needs PHASE_W and WEIGHT_W (CUBE4_GEOMETRY).
// A beat's slice geometry on the beat schedule, {stepx, stepy [DIM_W], ph_x,
// ph_y [PHASE_W]} (cube4_com_steps to cube4_com_beats), is CUBE4_GEO_W bits.
`define CUBE4_GEO_W (2 * DIM_W + 2 * PHASE_W)
`define CUBE4_PHASE_FUNCTIONS \
    function automatic [PHASE_W:0] phase_one(input [2:0] g); \
        phase_one = {{PHASE_W{1'b0}}, 1'b1} << (WEIGHT_W[3:0] + {1'b0, g}); \
    endfunction \
    function automatic [PHASE_W:0] phase_advance(input [PHASE_W-1:0] ph, input [WEIGHT_W:0] view, \
                                                 input [PHASE_W:0] one); \
        reg [PHASE_W:0] sum; \
        begin \
            sum = {1'b0, ph} + {{(PHASE_W - WEIGHT_W){1'b0}}, view}; \
            phase_advance = (sum >= one) ? {1'b1, sum[PHASE_W-1:0] - one[PHASE_W-1:0]} \
                                         : {1'b0, sum[PHASE_W-1:0]}; \
        end \
    endfunction

// The weight of the phase after ph is not 0, phase_advance(ph)[PHASE_W-1:0]
// >= g1 (a weight is phase >> g; numerics.md section 8), as compares of ph
// with three thresholds of the frame, so that no adder, wrap or shift lies
// before a unit's weight flag (they were the full build's longest path at
// P = 1 and 2). With one = 2^(W+g), g1 = 2^g:
//   ph + VIEW >= one + g1,  or  g1 <= ph + VIEW < one
//   <=>  ph >= t_c,  or  t_a <= ph < t_b,
//   t_a = g1 - VIEW, t_b = one - VIEW, t_c = one + g1 - VIEW, each clipped
//   at 0, in PHASE_W + 1 bits (one + g1 < 2^(PHASE_W+1)).
// CUBE4_PHASE_NEXT_NZ declares phase_thr3 ({t_c, t_b, t_a}), phase_next_nz
// and the registers ph_thr_x, ph_thr_y (the thresholds of VIEW_X, VIEW_Y),
// loaded every clk edge from cfg (stable in a frame). Needs
// CUBE4_PHASE_FUNCTIONS, clk, cfg_view_x, cfg_view_y and cfg_ss_log2.
`define CUBE4_PHASE_NEXT_NZ \
    function automatic [PHASE_W:0] phase_thr(input [PHASE_W:0] x, input [WEIGHT_W:0] view); \
        reg [PHASE_W+1:0] d; \
        begin \
            d = {1'b0, x} - {{(PHASE_W - WEIGHT_W + 1){1'b0}}, view}; \
            phase_thr = d[PHASE_W+1] ? {(PHASE_W + 1){1'b0}} : d[PHASE_W:0]; \
        end \
    endfunction \
    function automatic [3*PHASE_W+2:0] phase_thr3(input [WEIGHT_W:0] view, input [1:0] ssl); \
        reg [PHASE_W:0] one, g1; \
        begin \
            one = phase_one({1'b0, ssl}); \
            g1  = {{PHASE_W{1'b0}}, 1'b1} << ssl; \
            phase_thr3 = {phase_thr(one + g1, view), phase_thr(one, view), phase_thr(g1, view)}; \
        end \
    endfunction \
    function automatic phase_next_nz(input [PHASE_W-1:0] ph, input [3*PHASE_W+2:0] thr); \
        reg [PHASE_W:0] p; \
        begin \
            p = {1'b0, ph}; \
            phase_next_nz = (p >= thr[2*PHASE_W+2 +: PHASE_W+1]) \
                         || (p < thr[PHASE_W+1 +: PHASE_W+1] && p >= thr[0 +: PHASE_W+1]); \
        end \
    endfunction \
    reg [3*PHASE_W+2:0] ph_thr_x, ph_thr_y; \
    always @(posedge clk) begin \
        ph_thr_x <= phase_thr3(cfg_view_x, cfg_ss_log2); \
        ph_thr_y <= phase_thr3(cfg_view_y, cfg_ss_log2); \
    end

// ---------------------------------------------------------------- the next sample inside
// A ray's next sample along an axis, x + d (d its X- or Y-step, 0 or 1), lies
// inside: x + d < n, and not the last column (row) n - 1 of a template whose
// weight w (wx(m+1) > 0, wy(m+1) > 0) reads one beyond it: x + d + 1 != n
// (numerics.md section 8; cube4_com_walk, cube4_com_beats). As compares of x
// with n, n - 1 and n - 2 (registers of the frame's NI or NJ: n0, n1, n2),
// chosen by d, so no adder lies before them. Equal to the sums' test in IW
// bits for n >= 1 and x < 2^IW - 1 (n - 2 wraps where n = 1, and still
// agrees); positions stay below MAX_DIM + P - 1 < 2^IW - 2, and a frame with
// NI or NJ = 0 has no beats.
// CUBE4_NEXT_INSIDE declares the function, its rule from the four compares
// made elsewhere (next_inside_of: x < n0, x < n1, x == n1, x == n2; a unit
// that registers the compares a stage early) and the registers ni_0 .. ni_2,
// nj_0 .. nj_2 (NI, NJ and their n - 1, n - 2, loaded every clk edge). Needs
// IW (CUBE4_GEOMETRY), clk, and cfg_ni, cfg_nj (CUBE4_VIEW_FIELDS).
`define CUBE4_NEXT_INSIDE \
    function automatic next_inside_of(input d, input w, input lt0, input lt1, input eq1, input eq2); \
        next_inside_of = (d ? lt1 : lt0) && !(w && (d ? eq2 : eq1)); \
    endfunction \
    function automatic next_inside(input [IW-1:0] x, input d, input w, input [IW-1:0] n0, \
                                   input [IW-1:0] n1, input [IW-1:0] n2); \
        next_inside = next_inside_of(d, w, x < n0, x < n1, x == n1, x == n2); \
    endfunction \
    reg [IW-1:0] ni_0, ni_1, ni_2, nj_0, nj_1, nj_2; \
    always @(posedge clk) begin \
        ni_0 <= IW'(cfg_ni);  ni_1 <= IW'(cfg_ni) - IW'(1);  ni_2 <= IW'(cfg_ni) - IW'(2); \
        nj_0 <= IW'(cfg_nj);  nj_1 <= IW'(cfg_nj) - IW'(1);  nj_2 <= IW'(cfg_nj) - IW'(2); \
    end

// ---------------------------------------------------------------- lane arithmetic
// Lane q reads bank q and holds the position t of the partial beam with
// (c_i + c_j + c_k) mod P = q (Teramac paper, eq. 1), skew = (c_j + c_k) mod P:
//   t = (q - skew) mod P               i not flipped
//   t = (I_R1 + skew - q) mod P        i flipped
// mod_p normalises a value in (-P, 2P).
`define CUBE4_LANE_FUNCTIONS \
    function automatic [LANE_W-1:0] mod_p(input signed [LANE_W+2:0] v); \
        reg signed [LANE_W+2:0] w; \
        begin \
            w = v; \
            if (w < 0) w = w + $signed((LANE_W+3)'(P)); \
            if (w >= $signed((LANE_W+3)'(P))) w = w - $signed((LANE_W+3)'(P)); \
            mod_p = w[LANE_W-1:0]; \
        end \
    endfunction \
    function automatic [LANE_W-1:0] lane_pos(input integer q, input [LANE_W-1:0] skew, \
                                             input flip_i, input [LANE_W-1:0] i_r1); \
        begin \
            lane_pos = flip_i \
                ? mod_p($signed({3'b000, i_r1}) + $signed({3'b000, skew}) - $signed((LANE_W+3)'(q))) \
                : mod_p($signed((LANE_W+3)'(q)) - $signed({3'b000, skew})); \
        end \
    endfunction

// A row's last partial beam (cube4_cfb_decide, cube4_cfb_mask, cube4_gra_window;
// needs P, DIM_W, NB_W, LANE_W, IW): a row of NI columns has NB = ceil(NI / P)
// partial beams, the last L = NB - 1, and L holds the remainder NI - L P of them
// (1 .. P). A column i = pb P + t (0 <= t < P) is inside the row (i < NI) where
// pb < L, or pb = L and t < the remainder: so a unit tests i < NI as a compare of
// pb with L, both view constants, and no sum of the position is on the path.
`define CUBE4_LAST_BEAM_FUNCTIONS \
    function automatic [NB_W-1:0] row_last_pb(input [NB_W-1:0] nb_v); \
        row_last_pb = nb_v - 1'b1; \
    endfunction \
    function automatic [LANE_W:0] row_last_rem(input [DIM_W-1:0] ni_v, input [NB_W-1:0] nb_v); \
        row_last_rem = (LANE_W + 1)'(IW'(ni_v) - IW'(row_last_pb(nb_v)) * IW'(P)); \
    endfunction

// The traversal's steps along an axis (cube4_cfb_trav, cube4_cfb_bctl; needs
// CUBE4_LANE_FUNCTIONS and ADDR_W): r_step moves c mod P by +/-1 (down: -1);
// a_step moves the axis's address term A(c) with it (+/- LIN within a P-block,
// BLK across one: golden/cube4/memory.py); add_p = (a + b) mod P.
`define CUBE4_STEP_FUNCTIONS \
    function automatic [LANE_W-1:0] r_step(input [LANE_W-1:0] rr, input down); \
        reg [LANE_W:0] pl; \
        begin \
            pl = P[LANE_W:0]; \
            if (down) r_step = (rr == '0) ? pl[LANE_W-1:0] - 1'b1 : rr - 1'b1; \
            else      r_step = ({1'b0, rr} == pl - 1'b1) ? '0 : rr + 1'b1; \
        end \
    endfunction \
    function automatic [ADDR_W-1:0] a_step(input [ADDR_W-1:0] a, input [LANE_W-1:0] rr, \
                                           input down, input [ADDR_W-1:0] lin, \
                                           input [ADDR_W-1:0] blk); \
        reg [LANE_W:0] pl; \
        begin \
            pl = P[LANE_W:0]; \
            if (down) a_step = a - ((rr == '0) ? blk : lin); \
            else      a_step = a + (({1'b0, rr} == pl - 1'b1) ? blk : lin); \
        end \
    endfunction \
    function automatic [LANE_W-1:0] add_p(input [LANE_W-1:0] a, input [LANE_W-1:0] b); \
        add_p = mod_p($signed({3'b000, a}) + $signed({3'b000, b})); \
    endfunction

// The frame's log2 S and last sample slice M - 1 = (NK - 1) S from the view's
// fields (after CUBE4_VIEW_FIELDS; the beat schedule's units): log2 S is taken as 0
// in a build without supersampling (MAX_SS_LOG2 = 0), so its logic is S = 1's.
`define CUBE4_VIEW_SLICES \
    wire [1:0]     view_ssl    = (MAX_SS_LOG2 > 0) ? cfg_ss_log2 : 2'd0; \
    wire [M_W-1:0] view_m_last = M_W'(cfg_nk - 1'b1) << view_ssl

// The pass's slice terms at a pass's end (cube4_cfb_trav, cube4_cfb_bctl; needs
// CUBE4_STEP_FUNCTIONS, the view's fields and the registers rk_q, ak_q (the next
// voxel slice to read), rk0_q (the pass's lower slice), r_q (m mod S) and the flags
// any_read (the pass read a voxel slice) and last_r (r = S - 1)): the slice to read
// steps after a pass that read one; r wraps at S, and then the lower slice steps.
`define CUBE4_PASS_NEXT \
    if (any_read) begin \
        rk_q <= r_step(rk_q, cfg_flip_k); \
        ak_q <= a_step(ak_q, rk_q, cfg_flip_k, cfg_k_lin, cfg_k_blk); \
    end \
    if (last_r) begin \
        r_q   <= '0; \
        rk0_q <= r_step(rk0_q, cfg_flip_k); \
    end else begin \
        r_q <= r_q + 1'b1; \
    end

// ---------------------------------------------------------------- parameter checks
// A parameter outside its range stops elaboration (in a generate region):
//   "<module>: NAME = value is out of range LO..HI"
`define CUBE4_RANGE(LABEL, MODULE, NAME, VALUE, LO, HI) \
    if ((VALUE) < (LO) || (VALUE) > (HI)) begin : LABEL \
        $error("%s: %s = %0d is out of range %0d..%0d", MODULE, NAME, VALUE, LO, HI); \
    end

// In a generate region of a block that takes CUBE4_BUILD_PARAMS: the range of every
// build parameter (the one statement of the ranges; the rules between options are
// cube4_top's checks).
`define CUBE4_BUILD_CHECKS(MODULE) \
    `CUBE4_RANGE(g_bad_p, MODULE, "P", P, 1, 64) \
    `CUBE4_RANGE(g_bad_max_dim, MODULE, "MAX_DIM", MAX_DIM, 2, 2048) \
    `CUBE4_RANGE(g_bad_voxel_w, MODULE, "VOXEL_W", VOXEL_W, 1, 16) \
    `CUBE4_RANGE(g_bad_ss, MODULE, "MAX_SS_LOG2", MAX_SS_LOG2, 0, 3) \
    `CUBE4_RANGE(g_bad_weight_w, MODULE, "WEIGHT_W", WEIGHT_W, 4, 12) \
    `CUBE4_RANGE(g_bad_rmap_bits, MODULE, "RMAP_BITS", RMAP_BITS, 2, 6) \
    `CUBE4_RANGE(g_bad_alpha_w, MODULE, "ALPHA_W", ALPHA_W, 8, 16) \
    `CUBE4_RANGE(g_bad_acc_w, MODULE, "ACC_W", ACC_W, 8, 24) \
    `CUBE4_RANGE(g_bad_addr_w, MODULE, "ADDR_W", ADDR_W, 1, 30) \
    `CUBE4_RANGE(g_bad_shading, MODULE, "SHADING", SHADING, 0, 1) \
    `CUBE4_RANGE(g_bad_compositing, MODULE, "COMPOSITING", COMPOSITING, 0, 1) \
    `CUBE4_RANGE(g_bad_extremum, MODULE, "EXTREMUM", EXTREMUM, 0, 1) \
    `CUBE4_RANGE(g_bad_clip, MODULE, "CLIP", CLIP, 0, 1) \
    `CUBE4_RANGE(g_bad_vgrad, MODULE, "VGRAD", VGRAD, 0, 1) \
    `CUBE4_RANGE(g_bad_plw, MODULE, "PLW", PLW, 0, 1) \
    `CUBE4_RANGE(g_bad_rects, MODULE, "RECTS", RECTS, 0, 1) \
    `CUBE4_RANGE(g_bad_slab, MODULE, "SLAB", SLAB, 0, 1) \
    `CUBE4_RANGE(g_bad_zout, MODULE, "ZOUT", ZOUT, 0, 1) \
    `CUBE4_RANGE(g_bad_zin, MODULE, "ZIN", ZIN, 0, 1) \
    `CUBE4_RANGE(g_bad_gmod, MODULE, "GMOD", GMOD, 0, 1) \
    `CUBE4_RANGE(g_bad_labels, MODULE, "LABELS", LABELS, 0, 1) \
    `CUBE4_RANGE(g_bad_beats, MODULE, "BEATS", BEATS, 0, 1)

// ---------------------------------------------------------------- TRI units
// cube4_tri and its units (cube4_tri_src, _beam, _meta, _lane; docs/architecture.md "TRI").
//   CUBE4_TRI_PARAMS  the build parameters the top and its stages share, with the
//                     geometry, tag, word and TRI layouts derived from them
//   CUBE4_TRI_LAYOUT  (needs CUBE4_GEOMETRY and WEIGHT_W)
//     TRI_LERP_LAT    stages of one lerp (cube4_lerp LATENCY 4: b - a, the multiply,
//                     the product's fabric register, the add;
//                     CUBE4_TRI_LERP_LAT where no geometry is in scope)
//     TRI_CLIP_LAT    cube4_clip's latency from its fields to KEEP
//     TRI_C_*         a beat's fields that ride s0 .. s3 as one word, LSB first:
//                     the header (KEEP = LVALID), the lanes' wrap and neighbour
//                     flags, wz, wy, wx, emit; TRI_C_W bits
// cube4_sha_slab's latency from a beat's fields to its falloff weights (cube4_sha
// carries the beat that long at least when it builds the unit)
`define CUBE4_SLAB_LAT 9
// The beat schedule's lag (BEATS = 1; golden/cube4/beats.py LAG, numerics.md section 19):
// the decisions of slice m use COM's reports of slices up to m - LAG - 1. With GRA between
// the front end and COM it must be 4: COM finishes slice d once GRA has stepped slice
// d + 1 to its end, which it knows from a beat of slice d + 2; the walk may have to
// reach the end of slice d + 2 for that beat, fetching slice d + 3's rows, which needs
// the decisions of slice d + 4 (docs/architecture.md "Beat skipping and ray termination").
// COM counts a done ray's last LAG slices down in its buffer word (CUBE4_TERM_CNT_W).
`define CUBE4_BEAT_LAG 4
// CUBE4_TERM_CNT_W(LAG): the bits of a ray's termination state in COM's buffer
// word (cube4_com_lane): 0 live, LAG .. 1 the countdown after COM reported it
// done, LAG + 1 done without a countdown (it ends at its own stop)
`define CUBE4_TERM_CNT_W(LAG) $clog2((LAG) + 2)
// A beat's position bits {soon, last, fresh, run} [4P] (cube4_cfb_decide, the front end,
// COM), kept in 3P bits where they wait in block RAM (cube4_cfb_skip's queue, cube4_top's
// bits FIFO): last implies soon and fresh implies run, so per position {hi, lo} = 00 no
// run, 01 run, 10 run and soon, 11 run, soon and last, beside fresh; packed {hi, lo, fresh}
// (each [P]). Needs P.
`define CUBE4_RAY_BITS_FUNCTIONS \
    function automatic [3*P-1:0] ray_bits_pack(input [4*P-1:0] b); \
        ray_bits_pack = {b[3*P +: P], b[0 +: P] & (~b[3*P +: P] | b[2*P +: P]), b[P +: P]}; \
    endfunction \
    function automatic [4*P-1:0] ray_bits_unpack(input [3*P-1:0] k); \
        ray_bits_unpack = {k[2*P +: P], k[2*P +: P] & k[P +: P], k[0 +: P], k[2*P +: P] | k[P +: P]}; \
    endfunction
// Gradient-magnitude modulation (GMOD = 1; cube4_sha_gm, golden/cube4/gmod.py): the
// table's entries and address width for gradients of GW = VOXEL_W + 5 bits (s = |g|^2
// in 2 GW bits, 2^3 mantissa steps per bit position, entry 0 for s = 0), and the
// unit's latency from the gradient (stage a) to the factors (cube4_sha carries them on)
`define CUBE4_GM_LAT 7
`define CUBE4_GM_LAYOUT \
    localparam integer GM_MB  = 3, \
    localparam integer GM_N   = 2 * (VOXEL_W + 5) * (1 << GM_MB) + 1, \
    localparam integer GMA_W  = $clog2(GM_N), \
    localparam integer GMF_W  = 9
`define CUBE4_TRI_LERP_LAT 4
`define CUBE4_TRI_LAYOUT \
    localparam integer TRI_LERP_LAT = `CUBE4_TRI_LERP_LAT, \
    localparam integer TRI_CLIP_LAT = 5, \
    localparam integer TRI_C_WRAP   = HDR_W, \
    localparam integer TRI_C_NBR    = TRI_C_WRAP + P, \
    localparam integer TRI_C_WZ     = TRI_C_NBR + P, \
    localparam integer TRI_C_WY     = TRI_C_WZ + WEIGHT_W, \
    localparam integer TRI_C_WX     = TRI_C_WY + WEIGHT_W, \
    localparam integer TRI_C_EMIT   = TRI_C_WX + WEIGHT_W, \
    localparam integer TRI_C_W      = TRI_C_EMIT + 1
`define CUBE4_TRI_PARAMS \
    parameter integer P        = 8, parameter integer MAX_DIM     = 256, \
    parameter integer VOXEL_W  = 8, parameter integer MAX_SS_LOG2 = 0, \
    parameter integer WEIGHT_W = 8, parameter integer VGRAD       = 0, \
    parameter integer LABELS   = 0, \
    `CUBE4_GEOMETRY, `CUBE4_TAG_LAYOUT, `CUBE4_WORD_LAYOUT, `CUBE4_TRI_LAYOUT

// ---------------------------------------------------------------- CFB units
// CUBE4_CFB_PARAMS: the parameter list of cube4_cfb's units (cube4_cfb_*,
// docs/architecture.md "Front end"): the build parameters (ranges as
// cube4_cfb's) and CUBE4_CFB_LAYOUT: the layouts past the geometry and the
// view registers', CFB_R_W (bits of m mod S), CFB_F1_W (the tag without its
// lane masks), CFB_ADV_N copies of the beat pipeline's advance (cube4_cfb_mask:
// one per group of its loads, CFB_ADV_CTL the control and traversal (on the
// beat schedule its two stages and state), CFB_ADV_BITS the beat's bits
// beside the stages (BEATS), CFB_ADV_ADDR the address unit, CFB_ADV_MASK the
// mask's own stages, CFB_ADV_STEP the beat control's slice and row counters
// and the template's step (BEATS)), and the box's entry (cube4_cfb_box): CFB_BOX_FIXED marks the
// fields it holds at a constant, CFB_BOX_CONST (SBROW = 1, the rest 0).
// CUBE4_CFB_ADV_N is CFB_ADV_N, for the front end, which gives CFB its
// request's ready as that many equal copies (one per advance).
// CUBE4_CFB_PASS passes the build parameters on to a unit by name.
// CUBE4_CFB_ENTRY(e): a table entry as a unit reads it; without rectangles
// (RECTS = 0) the box's constant fields are constants, so that synthesis sees
// them past the units' boundaries. CUBE4_ADDR_FIELDS(bus): one wire
// cfg_<name> per address register, read from the address bus (module body).
`define CUBE4_CFB_ADV_N 5
`define CUBE4_CFB_BITS(W, POS) ((((RECT_W)'(1) << (W)) - (RECT_W)'(1)) << (POS))
`define CUBE4_CFB_LAYOUT \
    `CUBE4_ADDR_LAYOUT, `CUBE4_TAG_LAYOUT, `CUBE4_RECT_LAYOUT, \
    localparam integer CFB_R_W  = (MAX_SS_LOG2 > 0) ? MAX_SS_LOG2 : 1, \
    localparam integer CFB_F1_W = TAG_W - 4 * P, \
    localparam integer CFB_ADV_N = `CUBE4_CFB_ADV_N, localparam integer CFB_ADV_CTL = 0, localparam integer CFB_ADV_BITS = 1, \
    localparam integer CFB_ADV_ADDR = 2, localparam integer CFB_ADV_MASK = 3, localparam integer CFB_ADV_STEP = 4, \
    localparam [RECT_W-1:0] CFB_BOX_CONST = (RECT_W)'(1) << RT_SBROW, \
    localparam [RECT_W-1:0] CFB_BOX_FIXED = `CUBE4_CFB_BITS(1, RT_EMPTY) | `CUBE4_CFB_BITS(DIM_W, RT_J0) \
        | `CUBE4_CFB_BITS(DIM_W, RT_JIN) | `CUBE4_CFB_BITS(PB_W, RT_PB0) | `CUBE4_CFB_BITS(2 * DIM_W, RT_ILO) \
        | `CUBE4_CFB_BITS(IW + 2 * SB_W + DIM_W, RT_PBP0) | `CUBE4_CFB_BITS(RECT_W - RT_JHI, RT_JHI)
`define CUBE4_CFB_ENTRY(e) ((RECTS != 0) ? (e) : (((e) & ~CFB_BOX_FIXED) | CFB_BOX_CONST))
`define CUBE4_CFB_PARAMS \
    parameter integer P        = 8, parameter integer MAX_DIM     = 256, \
    parameter integer WEIGHT_W = 8, parameter integer MAX_SS_LOG2 = 0, \
    parameter integer ADDR_W   = 16, parameter integer RECTS       = 0, \
    `CUBE4_GEOMETRY, `CUBE4_VIEW_LAYOUT, `CUBE4_CFB_LAYOUT
`define CUBE4_CFB_PASS `CUBE4_SLICE_PASS, .ADDR_W(ADDR_W), .RECTS(RECTS)
`define CUBE4_ADDR_FIELDS(bus) \
    wire [ADDR_W-1:0] cfg_j_a0  = bus[ADR_J_A0 +: ADDR_W]; \
    wire [ADDR_W-1:0] cfg_j_lin = bus[ADR_J_LIN +: ADDR_W]; \
    wire [ADDR_W-1:0] cfg_j_blk = bus[ADR_J_BLK +: ADDR_W]; \
    wire [ADDR_W-1:0] cfg_k_a0  = bus[ADR_K_A0 +: ADDR_W]; \
    wire [ADDR_W-1:0] cfg_k_lin = bus[ADR_K_LIN +: ADDR_W]; \
    wire [ADDR_W-1:0] cfg_k_blk = bus[ADR_K_BLK +: ADDR_W]; \
    wire [ADDR_W-1:0] cfg_i_a0  = bus[ADR_I_A0 +: ADDR_W]; \
    wire [ADDR_W-1:0] cfg_i_pb  = bus[ADR_I_PB +: ADDR_W]; \
    wire [ADDR_W-1:0] cfg_i_lin = bus[ADR_I_LIN +: ADDR_W]

// CUBE4_CFB_TRAV_PORTS, _CTL_PORTS, _MASK_PORTS: the ports of those units past
// clk, rst and the register buses (declared once for the unit and its harness).
`define CUBE4_CFB_TRAV_PORTS \
    input  wire [RECT_W-1:0] rt_cur, input wire [RECT_W-1:0] rt_nxt, \
    input  wire idle, input wire advance, input wire pass_next, input wire row, input wire flush_row, \
    output wire [M_W-1:0] m, output wire k0_odd, output wire [CFB_R_W-1:0] r, \
    output wire [DIM_W-1:0] j, output wire [PB_W-1:0] pb, output wire [SB_W-1:0] sb, \
    output wire [IW-1:0] pbp, output wire [ADDR_W-1:0] pbx, \
    output wire [ADDR_W-1:0] aj, output wire [ADDR_W-1:0] ak, \
    output wire last_pb, output wire last_j, output wire last_pass, \
    output wire lower_mem, output wire upper_mem, \
    output wire [LANE_W-1:0] skew_rd, output wire [LANE_W-1:0] skew_pas, output wire [LANE_W-1:0] skew_vrt
`define CUBE4_CFB_CTL_PORTS \
    input  wire start, input wire busy, input wire advance, \
    input  wire [RECT_W-1:0] rt_cur, input wire [RECT_W-1:0] rt_nxt, \
    input  wire [M_W-1:0] m, input wire k0_odd, input wire [CFB_R_W-1:0] r, \
    input  wire [DIM_W-1:0] j, input wire [PB_W-1:0] pb, input wire [SB_W-1:0] sb, \
    input  wire last_pb, input wire last_j, input wire lower_mem, input wire upper_mem, \
    input  wire [LANE_W-1:0] skew_pas, input wire [LANE_W-1:0] skew_vrt, \
    input  wire [WEIGHT_W-1:0] wx, input wire [WEIGHT_W-1:0] wy, input wire [WEIGHT_W-1:0] wz, \
    input  wire [3:0] steps, \
    output wire idle, output wire go, output wire next_pass, output wire pass_done, \
    output wire pass_next, output wire row, output wire flush_row, \
    output wire issue, output wire [CFB_F1_W-1:0] fields, \
    output wire use_prev, output wire [LANE_W-1:0] skew_out, \
    output wire [DIM_W-1:0] p_ilo, output wire [DIM_W-1:0] p_iin, output wire [DIM_W-1:0] p_ihi, \
    output wire rowv, output wire rowin, output wire rd
`define CUBE4_CFB_MASK_PORTS \
    input  wire idle, input wire issue, input wire [CFB_F1_W-1:0] fields, \
    input  wire use_prev, input wire [LANE_W-1:0] skew_out, \
    input  wire [DIM_W-1:0] p_ilo, input wire [DIM_W-1:0] p_iin, input wire [DIM_W-1:0] p_ihi, \
    input  wire rowv, input wire rowin, input wire rd, \
    input  wire [RECT_W-1:0] rt_cur, input wire [IW-1:0] pbp, input wire [P*LANE_W-1:0] t1, \
    output wire [CFB_ADV_N-1:0] advance, output wire busy, \
    output wire req_valid, input wire [CFB_ADV_N-1:0] req_ready, \
    output wire [P-1:0] req_rden, output wire [TAG_W-1:0] req_tag

// The voxel memory's ports (cube4_voxel_mem on chip, cube4_dram_fetch in front of a
// DRAM): the load port (one word per bank at the same address), read requests (an
// address and a read enable per bank, a tag) and responses (the words, 0 where not
// read, the request's tag). No trailing comma.
`define CUBE4_VOXEL_MEM_PORTS \
    input  wire ld_valid, output wire ld_ready, \
    input  wire [ADDR_W-1:0] ld_addr, input wire [P*WORD_W-1:0] ld_data, \
    input  wire req_valid, output wire req_ready, input wire [TAG_W-1:0] req_tag, \
    input  wire [P*ADDR_W-1:0] req_addr, \
    input  wire [P-1:0] req_rden, \
    output wire rsp_valid, input wire rsp_ready, output wire [TAG_W-1:0] rsp_tag, \
    output wire [P*WORD_W-1:0] rsp_data

// A stream block's clock, reset, input and output streams of W-bit items
// (cube4_skid, cube4_sync_fifo). No trailing comma.
`define CUBE4_STREAM_PORTS(W) \
    input  wire clk, input wire rst, \
    input  wire in_valid, output wire in_ready, input wire [W-1:0] in_data, \
    output wire out_valid, input wire out_ready, output wire [W-1:0] out_data

// cube4_top's connections of its voxel memory (either kind): the load port from the
// top's ports, the front end's requests and the responses to it. No trailing comma.
`define CUBE4_VOXEL_MEM_CONNECT \
    .ld_valid  (ld_valid),      .ld_ready  (ld_ready), \
    .ld_addr   (ld_addr),       .ld_data   (ld_data), \
    .req_valid (mem_req_valid), .req_ready (mem_req_ready), \
    .req_addr  (req_addr),      .req_rden  (req_rden),      .req_tag (req_tag), \
    .rsp_valid (mem_rsp_valid), .rsp_ready (mem_rsp_ready), \
    .rsp_data  (rsp_data),      .rsp_tag   (rsp_tag)

// The DRAM port connected to signals of its own names (cube4_top to cube4_dram_fetch,
// the harness to cube4_top). No trailing comma.
`define CUBE4_DRAM_CONNECT \
    .dram_cmd_valid   (dram_cmd_valid),   .dram_cmd_ready   (dram_cmd_ready), \
    .dram_cmd_we      (dram_cmd_we),      .dram_cmd_addr    (dram_cmd_addr), \
    .dram_wdata_valid (dram_wdata_valid), .dram_wdata_ready (dram_wdata_ready), \
    .dram_wdata_data  (dram_wdata_data),  .dram_wdata_we    (dram_wdata_we), \
    .dram_rdata_valid (dram_rdata_valid), .dram_rdata_ready (dram_rdata_ready), \
    .dram_rdata_data  (dram_rdata_data)

// The DRAM controller's native port as the pipelines see it (cube4_top and
// cube4_dram_fetch; LiteDRAM's: commands, write data and read data as streams,
// 128-bit words of one BL8 burst, write enables per byte, read data in command
// order and never held back). No trailing comma.
`define CUBE4_DRAM_PORTS \
    output wire                 dram_cmd_valid, \
    input  wire                 dram_cmd_ready, \
    output wire                 dram_cmd_we, \
    output wire [DRAM_AW-1:0]   dram_cmd_addr, \
    output wire                 dram_wdata_valid, \
    input  wire                 dram_wdata_ready, \
    output wire [127:0]         dram_wdata_data, \
    output wire [15:0]          dram_wdata_we, \
    input  wire                 dram_rdata_valid, \
    output wire                 dram_rdata_ready, \
    input  wire [127:0]         dram_rdata_data

`endif
