"""The host side of the skewed voxel memory (cube4.memory)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from cube4.memory import (address_of, bank_of, frontend_regs, lane_positions, load_image, pack_volume,
                          unpack_volume, words_per_bank, write_hex)
from cube4.view import make_traversal

DIMS = [(4, 4, 4), (13, 7, 5), (5, 9, 3), (1, 1, 1), (17, 2, 11)]


@pytest.mark.parametrize("p", [1, 2, 3, 4, 5, 8, 16])
@pytest.mark.parametrize("dims", DIMS)
def test_pack_roundtrip_and_layout(p, dims):
    """Each voxel in its own (bank, address); in another axis order the image is the
    volume's with its axes permuted, the bank of every voxel unchanged."""
    rng = np.random.default_rng(1)
    nx, ny, nz = dims
    vol = rng.integers(0, 4096, size=(nz, ny, nx))
    banks = pack_volume(vol, p)
    assert banks.shape == (p, words_per_bank(dims, p))
    assert (unpack_volume(banks, dims) == vol).all()
    # every voxel has its own (bank, address): the layout is a bijection onto the used words
    z, y, x = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")
    key = bank_of(x, y, z, p) * banks.shape[1] + address_of(x, y, z, dims, p)
    assert np.unique(key).size == vol.size
    # padding words (x beyond nx) hold zero
    assert banks.sum() == vol.sum()
    for order in ((1, 0, 2), (0, 2, 1), (1, 2, 0), (2, 0, 1)):
        t = pack_volume(vol, p, order)
        assert t.shape == (p, words_per_bank(dims, p, order))
        assert (t[bank_of(x, y, z, p), address_of(x, y, z, dims, p, order)] == vol).all()


@pytest.mark.parametrize("p", [2, 5, 8])
def test_any_p_consecutive_voxels_on_any_axis_hit_distinct_banks(p):
    """The skew's purpose (Teramac eq. 1): a partial beam along x, y or z is conflict free."""
    for axis in range(3):
        for start in range(3 * p):
            c = np.zeros((3, p), dtype=np.int64) + np.array([[3], [1], [2]])
            c[axis] = start + np.arange(p)
            assert np.unique(bank_of(*c, p)).size == p


@pytest.mark.parametrize("p", [1, 3, 4, 5, 8])
def test_frontend_regs_reproduce_the_layout(p):
    """Address = A_j + A_k + I_A0 +/- (pb*I_PB + t*I_LIN + [t > I_RT]) with the
    incremental axis terms equals address_of for every voxel and every view class."""
    dims = (11, 6, 7)
    for major, signs in itertools.product(range(3), range(8)):
        d = [(-1.0 if (signs >> a) & 1 else 1.0) * (1.0 if a == major else 0.5) for a in range(3)]
        trav = make_traversal(dims, d)
        r = frontend_regs(trav, p)
        assert r["NB"] == -(-trav.ni // p)

        def walk(a0, lin, blk, r0, steps, down):
            a, rr = a0, r0
            out = [a]
            for _ in range(steps):
                if down:
                    a -= blk if rr == 0 else lin
                    rr = p - 1 if rr == 0 else rr - 1
                else:
                    a += blk if rr == p - 1 else lin
                    rr = 0 if rr == p - 1 else rr + 1
                out.append(a)
            return out

        aj = walk(r["J_A0"], r["J_LIN"], r["J_BLK"], r["J_R0"], trav.nj - 1, r["FLIP_J"])
        ak = walk(r["K_A0"], r["K_LIN"], r["K_BLK"], r["K_R0"], trav.nk - 1, r["FLIP_K"])
        for k, j, i in itertools.product(range(trav.nk), range(trav.nj), range(trav.ni)):
            pb, t = divmod(i, p)
            off = pb * r["I_PB"] + t * r["I_LIN"] + (t > r["I_RT"])
            a = aj[j] + ak[k] + (r["I_A0"] - off if r["FLIP_I"] else off)
            x, y, z = trav.traversal_to_volume_points(i, j, k).round().astype(int)
            assert a == address_of(x, y, z, dims, p), (d, p, (i, j, k))


@pytest.mark.parametrize("p", [1, 2, 3, 4, 5, 8, 16])
@pytest.mark.parametrize("ni", [1, 7, 13, 32])
def test_lane_positions_match_banks(p, ni):
    """Where the P lanes of a beat sit along the beam, for every skew and partial beam:
    lane q holds the position whose bank is q, and over a row's partial beams every
    position 0 .. NB*P - 1 is held once (positions >= ni are padding)."""
    nb = -(-ni // p)
    for flip_i in (False, True):
        for skew in range(p):
            pos = np.stack([lane_positions(skew, pb, p, ni, flip_i) for pb in range(nb)])
            assert sorted(pos.reshape(-1)) == list(range(nb * p))
            for pb in range(nb):
                assert sorted(pos[pb]) == list(range(pb * p, (pb + 1) * p))
                c_i = (ni - 1 - pos[pb]) if flip_i else pos[pb]
                assert ((c_i + skew) % p == np.arange(p)).all()


def test_load_image_interleaves_the_banks():
    """Line a * p + q of the image is word a of bank q (the harnesses' load order)."""
    vol = np.arange(2 * 3 * 5).reshape(2, 3, 5) * 100
    banks = pack_volume(vol, 4)
    img = load_image(banks)
    assert img.size == banks.size
    for q, a in itertools.product(range(4), range(banks.shape[1])):
        assert img[a * 4 + q] == banks[q, a]


def test_write_hex(tmp_path):
    """The one $readmemh writer: fixed width, one word per line, nothing left behind."""
    path = write_hex(tmp_path / "m.hex", np.array([0, 5, 4095, 256]), 12)
    assert path.read_text() == "000\n005\nfff\n100\n"
    assert write_hex(tmp_path / "t.hex", [0x3FF, 1], 10).read_text() == "3ff\n001\n"  # 10 bits: 3 digits
    assert write_hex(tmp_path / "e.hex", [], 8).read_text() == ""
    with pytest.raises(ValueError, match="does not fit in 12"):
        write_hex(tmp_path / "bad.hex", [4096], 12)
    with pytest.raises(ValueError, match="does not fit"):
        write_hex(tmp_path / "neg.hex", [-1], 12)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["e.hex", "m.hex", "t.hex"]


@pytest.mark.parametrize("order", [(0, 1, 2), (0, 2, 1), (1, 2, 0), (2, 1, 0)])
@pytest.mark.parametrize("p", [1, 3, 4, 5, 8])
def test_frontend_regs_reach_a_crop_box(p, order):
    """A box (crop or brick) at an origin inside a larger volume is traversed by start
    addresses and lane residues alone: every voxel's address is address_of in the whole
    volume, and the lane that reads it (bank (t + skew) mod p, skew = the CFB's
    J residue + K residue, t its position in the partial beam; flipped i: t from the
    box's far end) is the bank that holds it. In every axis order of the image (a DRAM
    build holds three), placed at a base word."""
    vol_dims = (13, 9, 10)
    rng = np.random.default_rng(p)
    for major, signs in itertools.product(range(3), range(8)):
        box = tuple(int(rng.integers(2, n + 1)) for n in vol_dims)
        org = tuple(int(rng.integers(0, n - b + 1)) for n, b in zip(vol_dims, box))
        d = [(-1.0 if (signs >> a) & 1 else 1.0) * (1.0 if a == major else 0.5) for a in range(3)]
        trav = make_traversal(box, d, origin=org)
        base = 0 if order == (0, 1, 2) else 1000
        r = frontend_regs(trav, p, vol_dims, order=order, base=base)

        def walk(a0, lin, blk, r0, steps, down):
            a, rr = a0, r0
            out = [(a, rr)]
            for _ in range(steps):
                if down:
                    a -= blk if rr == 0 else lin
                    rr = p - 1 if rr == 0 else rr - 1
                else:
                    a += blk if rr == p - 1 else lin
                    rr = 0 if rr == p - 1 else rr + 1
                out.append((a, rr))
            return out

        aj = walk(r["J_A0"], r["J_LIN"], r["J_BLK"], r["J_R0"], trav.nj - 1, r["FLIP_J"])
        ak = walk(r["K_A0"], r["K_LIN"], r["K_BLK"], r["K_R0"], trav.nk - 1, r["FLIP_K"])
        for k, j, i in itertools.product(range(trav.nk), range(trav.nj), range(trav.ni)):
            pb, t = divmod(i, p)
            off = pb * r["I_PB"] + t * r["I_LIN"] + (t > r["I_RT"])
            a = aj[j][0] + ak[k][0] + (r["I_A0"] - off if r["FLIP_I"] else off)
            x, y, z = trav.traversal_to_volume_points(i, j, k).round().astype(int)
            assert a == base + address_of(x, y, z, vol_dims, p, order), (d, p, org, box, (i, j, k))
            skew = (aj[j][1] + ak[k][1]) % p
            # lane_pos inverted: t = (q - skew) mod p, or (I_R1 + skew - q) mod p flipped
            lane = ((r["I_R1"] + skew - t) if r["FLIP_I"] else (t + skew)) % p
            assert lane_positions(skew, pb, p, trav.ni, bool(r["FLIP_I"]))[lane] == i
            assert bank_of(x, y, z, p) == lane, (d, p, org, box, (i, j, k))
