"""cocotb 2.x bench of sm_top with the ecosystem's verification IP (cocotbext-axi).

An AxiLiteMaster programs the registers the project's own host code writes (the
register file tests/cocotb/small_regs.json as sim/sm_regs_io.hpp turns it into words),
an AxiStreamSource streams the camera frames (one packet per line, tuser on the
frame's first pixel), two AxiStreamSinks take the disparity stream and the object
packets. Every channel has a random pause generator: tvalid gaps on the camera and on
AW/W/AR, tready back-pressure on both outputs and on B/R. The disparity words and the
object packets must equal the reference model's (tools/sm_ref_frames wrote them, with
the camera words, into the JSON named by SM_REF_JSON); STATUS must count the frames,
ERR_FLAGS and the error counters must stay 0. A monitor checks the AXI4-Stream rules
on both outputs on every clock (TVALID low in reset; once TVALID is high it stays high,
with TDATA/TUSER/TLAST unchanged, until the handshake), and the output sinks raise
TREADY only after they saw TVALID, so a TVALID that waits for TREADY deadlocks.

Run by tests/cocotb/run_sm_top.py (ctest system_cocotb_small); docs/verification.md.
"""

import json
import logging
import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, Combine, ReadOnly, RisingEdge, with_timeout
from cocotbext.axi import (
    AxiLiteBus,
    AxiLiteMaster,
    AxiResp,
    AxiStreamBus,
    AxiStreamFrame,
    AxiStreamSink,
    AxiStreamSource,
)

SEED = int(os.environ.get("SM_COCOTB_SEED", "24"))


def pauses(rng, percent):
    """A pause generator: True (pause this clock) with the given probability."""
    while True:
        yield rng.randrange(100) < percent


def ready_after_valid(rng, percent, tvalid):
    """A sink's pause generator that also waits for TVALID before raising TREADY (allowed
    to a slave; a master must not wait for TREADY before raising TVALID, so a TVALID that
    depends on TREADY deadlocks here)."""
    while True:
        yield not int(tvalid.value) or rng.randrange(100) < percent


class StreamRules:
    """AXI4-Stream rules of one master interface of the DUT, checked every clock."""

    def __init__(self, dut, prefix, signals):
        self.name = prefix
        self.valid = getattr(dut, prefix + "_tvalid")
        self.ready = getattr(dut, prefix + "_tready")
        self.payload = [(s, getattr(dut, f"{prefix}_{s}")) for s in signals]
        self.errors = []

    def error(self, msg):
        if len(self.errors) < 10:
            self.errors.append(f"{self.name}: {msg}")

    async def run(self, clk, rstn):
        held = None  # payload of a beat offered and not taken at the last edge
        while True:
            await RisingEdge(clk)
            await ReadOnly()
            valid = int(self.valid.value)
            if not int(rstn.value):
                if valid:
                    self.error("TVALID high while ARESETn is low")
                held = None
                continue
            now = {s: int(sig.value) for s, sig in self.payload}
            if held is not None:
                if not valid:
                    self.error("TVALID dropped before the handshake")
                elif now != held:
                    self.error(f"payload changed before the handshake: {held} -> {now}")
            held = now if valid and not int(self.ready.value) else None


async def axil_write(axil, addr, value, name):
    resp = await axil.write(addr, value.to_bytes(4, "little"))
    assert resp.resp == AxiResp.OKAY, f"write {name} @0x{addr:04x} answered {resp.resp}"


async def axil_read(axil, addr, name):
    resp = await axil.read(addr, 4)
    assert resp.resp == AxiResp.OKAY, f"read {name} @0x{addr:04x} answered {resp.resp}"
    return int.from_bytes(resp.data, "little")


@cocotb.test()
async def frames_match_model(dut):
    with open(os.environ["SM_REF_JSON"]) as f:
        ref = json.load(f)
    rng = random.Random(SEED)
    w, h = ref["width"], ref["height"]
    frames = ref["frames"]
    addr = ref["addr"]

    cocotb.start_soon(Clock(dut.aclk, 10, unit="ns").start())
    dut.aresetn.value = 0
    # no tkeep: one "byte" per beat, as wide as TDATA (a pixel pair, a disparity, a word)
    rst = dict(reset_active_level=False)
    source = AxiStreamSource(AxiStreamBus.from_prefix(dut, "s_axis"), dut.aclk, dut.aresetn, byte_size=16, **rst)
    disp_sink = AxiStreamSink(AxiStreamBus.from_prefix(dut, "m_axis"), dut.aclk, dut.aresetn, byte_size=32, **rst)
    obj_sink = AxiStreamSink(AxiStreamBus.from_prefix(dut, "m_axis_obj"), dut.aclk, dut.aresetn, byte_size=32, **rst)
    axil = AxiLiteMaster(AxiLiteBus.from_prefix(dut, "s_axil"), dut.aclk, dut.aresetn, **rst)
    for ifc in (source, disp_sink, obj_sink, axil.write_if, axil.read_if):
        ifc.log.setLevel(logging.WARNING)
    # random gaps and back-pressure on every channel
    source.set_pause_generator(pauses(rng, 30))
    disp_sink.set_pause_generator(ready_after_valid(rng, 30, dut.m_axis_tvalid))
    obj_sink.set_pause_generator(ready_after_valid(rng, 50, dut.m_axis_obj_tvalid))
    for ch in (axil.write_if.aw_channel, axil.write_if.w_channel, axil.write_if.b_channel):
        ch.set_pause_generator(pauses(rng, 40))
    for ch in (axil.read_if.ar_channel, axil.read_if.r_channel):
        ch.set_pause_generator(pauses(rng, 40))
    rules = [
        StreamRules(dut, "m_axis", ["tdata", "tuser", "tlast"]),
        StreamRules(dut, "m_axis_obj", ["tdata", "tlast"]),
    ]
    for r in rules:
        cocotb.start_soon(r.run(dut.aclk, dut.aresetn))

    await ClockCycles(dut.aclk, 8)
    dut.aresetn.value = 1
    await ClockCycles(dut.aclk, 2)

    for name, want in ref["expect"].items():
        got = await axil_read(axil, addr[name], name)
        assert got == want, f"{name} = 0x{got:08x}, expected 0x{want:08x}"
    for wr in ref["writes"]:
        await axil_write(axil, wr["addr"], wr["value"], wr["name"])

    async def camera():
        for f in frames:
            cam = f["camera"]
            for y in range(h):
                line = cam[y * w : (y + 1) * w]
                await source.send(AxiStreamFrame(line, tuser=[1 if y == 0 else 0] + [0] * (w - 1)))
        await source.wait()

    async def disparity():
        for n, f in enumerate(frames):
            got = []
            for y in range(h):
                line = await disp_sink.recv(compact=False)
                assert len(line.tdata) == w, f"frame {n} line {y}: {len(line.tdata)} beats, expected {w} (tlast)"
                tuser = line.tuser if isinstance(line.tuser, list) else [line.tuser] * w
                want_user = [1 if y == 0 else 0] + [0] * (w - 1)
                assert [int(u) for u in tuser] == want_user, f"frame {n} line {y}: tuser {tuser}"
                got += list(line.tdata)
            bad = [i for i in range(w * h) if got[i] != f["disp"][i]]
            assert not bad, (
                f"frame {n}: {len(bad)} disparity words differ from the model, first at "
                f"({bad[0] % w}, {bad[0] // w}): 0x{got[bad[0]]:08x} != 0x{f['disp'][bad[0]]:08x}"
            )
            dut._log.info("frame %d: %d x %d disparity words equal the model's", n, w, h)

    async def objects():
        for n, f in enumerate(frames):
            pkt = await obj_sink.recv()
            assert list(pkt.tdata) == f["packet"], f"frame {n}: object packet {list(pkt.tdata)} != {f['packet']}"
            dut._log.info("frame %d: object packet (%d objects) equals the model's", n, f["objects"])

    cam = cocotb.start_soon(camera())
    # about 1.6 clocks per pixel here; 6 leaves room for other seeds, and a deadlock fails fast
    timeout_us = 6 * len(frames) * w * h * 10 // 1000 + 200
    await with_timeout(Combine(cam, cocotb.start_soon(disparity()), cocotb.start_soon(objects())), timeout_us, "us")
    await ClockCycles(dut.aclk, 20)

    status = await axil_read(axil, addr["STATUS"], "STATUS")
    assert status & 0xFFFF == len(frames), f"STATUS.FRAME_COUNT {status & 0xFFFF}, expected {len(frames)}"
    for name in ("ERR_FLAGS", "ERR_CNT_LINE", "ERR_CNT_SOF", "ERR_CNT_ROWS", "ERR_CNT_OUT"):
        v = await axil_read(axil, addr[name], name)
        assert v == 0, f"{name} = 0x{v:08x}, expected 0"
    # the object list of the last frame over AXI4-Lite: OBJ_HEADER {table_full, too_many,
    # valid, count} against the packet header {lost, table_full, too_many, count}
    header = await axil_read(axil, addr["OBJ_HEADER"], "OBJ_HEADER")
    p = frames[-1]["packet"][0]
    want = (p & 0xFF) | 0x100 | ((p >> 8) & 1) << 9 | ((p >> 9) & 1) << 10
    assert header & 0x7FF == want, f"OBJ_HEADER 0x{header:08x}, expected 0x{want:03x} (last frame's list)"
    assert not disp_sink.count() and not obj_sink.count(), "beats after the last frame"
    errors = [e for r in rules for e in r.errors]
    assert not errors, "AXI4-Stream rules broken:\n" + "\n".join(errors)
