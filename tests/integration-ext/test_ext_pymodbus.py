#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Extended function set (docs/extended-functions.md) with pymodbus (Debian's python3-pymodbus, 3.0 API)
against modcp-sim with configs/default.ini, comm-loss supervision 500 ms:

 - FC08 through pymodbus's diag_message requests: echo, clear counters, the eight
   counters after known traffic (good requests, an exception, CRC-corrupted frames and
   a frame for another slave sent raw on the same line), diagnostic register, change
   ASCII delimiter, force listen-only (nothing answered or executed; the console shows
   listen_only=1), restart communications (leaves listen-only), clear overrun;
 - FC11 get comm event counter, FC12 get comm event log (exact event bytes);
 - FC43/14 read device identification (basic, regular, individual, exception 02);
 - comm-loss supervision: armed by a write, (0E)60H and commloss=1 on the console
   after 500 ms of silence, latched through requests, cleared by `commloss reset`.

    test_ext_pymodbus.py --sim PATH/modcp-sim --config configs/default.ini --simlib DIR
"""
import argparse
import os
import sys
import time


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--config", required=True)
    ap.add_argument("--simlib", required=True)
    ap.add_argument("--modcp-version", required=True,
                    help="project(modcp VERSION): FC43 object 02 (the revision is left empty)")
    ap.add_argument("--baud", type=int, default=38400)
    a = ap.parse_args()
    sys.path.insert(0, a.simlib)
    from simlib import Checks, RawLine, Sim, with_crc  # noqa: E402
    import debpkg  # noqa: E402
    try:
        from pymodbus import diag_message as dm
        from pymodbus.client import ModbusSerialClient
        from pymodbus.mei_message import ReadDeviceInformationRequest
        from pymodbus.other_message import GetCommEventCounterRequest, GetCommEventLogRequest
        from pymodbus.pdu import ExceptionResponse
    except ImportError as e:
        debpkg.missing(e)

    t = Checks()
    S = 5
    sim = Sim(a.sim, a.config, sets=["serial.baud=%d" % a.baud, "supervision.commloss_ms=500"],
              cycle_ms=1).start()

    def client():
        for parity in ("E", "N"):  # a pty refuses parity with Debian's glibc
            c = ModbusSerialClient(port=sim.device, baudrate=a.baud, parity=parity, stopbits=1,
                                   bytesize=8, timeout=1, retries=0, retry_on_empty=False)
            try:
                if c.connect():
                    return c
            except Exception:
                pass
            try:
                c.close()
            except Exception:
                pass
        raise RuntimeError("cannot open " + sim.device)

    def raw(frames):
        """Frames written raw (no reply expected), the pymodbus client closed meanwhile."""
        line = RawLine(sim.device)
        try:
            for f in frames:
                time.sleep(0.02)
                line.send(f)
                time.sleep(0.05)
            line.flush()
        finally:
            line.close()

    def diag(req):
        rr = c.execute(req)
        if isinstance(rr, ExceptionResponse) or not hasattr(rr, "message"):
            return None
        m = rr.message
        return m[0] if isinstance(m, (list, tuple)) and m else m

    def status():
        return sim.status()

    c = client()
    try:
        # -- FC08 counters after known traffic --------------------------------------------
        echo = diag(dm.ReturnQueryDataRequest(message=0xA5C3, unit=S))
        t.ok(echo == 0xA5C3, "FC08 00 echo A5C3 (%r)" % echo)
        t.ok(diag(dm.ClearCountersRequest(unit=S)) == 0, "FC08 0A clear counters (echo 0000)")
        for _ in range(3):
            rr = c.read_holding_registers(0x50, 2, slave=S)
            t.ok(not rr.isError() and rr.registers == [0x8765, 0x4321], "FC03 DB800.DBW160")
        rr = c.read_holding_registers(0x600, 1, slave=S)  # DB803 does not exist
        t.ok(isinstance(rr, ExceptionResponse) and rr.exception_code == 4, "FC03 DB803 -> 04")
        c.close()
        bad = bytearray(with_crc("05 03 00 50 00 02"))
        bad[-1] ^= 0x5A
        raw([bytes(bad), bytes(bad), with_crc("07 03 00 50 00 02")])
        c = client()
        expect = [(dm.ReturnBusMessageCountRequest, 6, "0B bus messages: 3 + exc + slave 7 + itself"),
                  (dm.ReturnBusCommunicationErrorCountRequest, 2, "0C CRC errors"),
                  (dm.ReturnBusExceptionErrorCountRequest, 1, "0D exceptions"),
                  (dm.ReturnSlaveMessageCountRequest, 8, "0E slave messages: 4 + 0B..0E"),
                  (dm.ReturnSlaveNoResponseCountRequest, 0, "0F no response"),
                  (dm.ReturnSlaveNAKCountRequest, 0, "10 NAK"),
                  (dm.ReturnSlaveBusyCountRequest, 0, "11 busy"),
                  (dm.ReturnSlaveBusCharacterOverrunCountRequest, 0, "12 overrun")]
        for cls, want, what in expect:
            got = diag(cls(unit=S))
            t.ok(got == want, "FC08 %s = %r (expected %d)" % (what, got, want))
        st = status()
        t.ok(st.get("bus_crc") == "2" and st.get("exceptions") == "1",
             "console: bus_crc=%s exceptions=%s" % (st.get("bus_crc"), st.get("exceptions")))
        t.ok(diag(dm.ReturnDiagnosticRegisterRequest(unit=S)) == 0, "FC08 02 diagnostic register 0000")
        t.ok(diag(dm.ClearOverrunCountRequest(unit=S)) == 0, "FC08 14 clear overrun (echo)")
        t.ok(diag(dm.ChangeAsciiInputDelimiterRequest(data=0x3B00, unit=S)) == 0x3B00,
             "FC08 03 change ASCII delimiter to ';' (echo 3B00)")

        # -- FC11 -----------------------------------------------------------------------------
        rr = c.execute(GetCommEventCounterRequest(unit=S))
        # 3 reads, 8 counter reads, 02, 14, 03 completed without exception
        t.ok(not rr.isError() and rr.status and rr.count == 14,
             "FC11 status ready, count %r (expected 14)" % getattr(rr, "count", None))

        # -- listen-only ----------------------------------------------------------------------
        rr = c.execute(dm.ForceListenOnlyModeRequest(unit=S))
        t.ok(rr is None or rr.isError(), "FC08 04 force listen-only: no reply")
        st = status()
        t.ok(st.get("listen_only") == "1", "console: listen_only=%s" % st.get("listen_only"))
        rr = c.write_register(0x64, 0x4444, slave=S)
        t.ok(rr is None or rr.isError(), "FC06 in listen-only: no reply")
        t.ok(sim.get("DB800.DBW200") != 0x4444, "FC06 in listen-only: not executed")
        rr = c.execute(dm.RestartCommunicationsOptionRequest(toggle=False, unit=S))
        t.ok(rr is None or rr.isError(), "FC08 01 in listen-only: processed without a reply")
        st = status()
        t.ok(st.get("listen_only") == "0", "console: listen_only=%s after the restart"
             % st.get("listen_only"))
        rr = c.read_holding_registers(0x50, 1, slave=S)
        t.ok(not rr.isError() and rr.registers == [0x8765], "FC03 answered again")

        # -- FC12: restart with clear log, then known traffic ------------------------------------
        rr = c.execute(dm.RestartCommunicationsOptionRequest(toggle=True, unit=S))
        t.ok(rr is not None and not rr.isError(), "FC08 01 FF00 restart, clear log: echo")
        c.read_holding_registers(0x50, 1, slave=S)
        c.write_register(0xC800, 1, slave=S)  # DB900: exception 02
        rr = c.execute(GetCommEventLogRequest(unit=S))
        ev = getattr(rr, "events", None)
        t.ok(not rr.isError() and rr.status and rr.event_count == 1 and rr.message_count == 3
             and ev == [0x80, 0x41, 0x80, 0x40, 0x80, 0x00],
             "FC12 event count %r, message count %r, events %r (1, 3, [80 41 80 40 80 00])"
             % (getattr(rr, "event_count", None), getattr(rr, "message_count", None),
                [hex(e) for e in ev or []]))

        # -- FC43/14 --------------------------------------------------------------------------------
        rr = c.execute(ReadDeviceInformationRequest(read_code=1, object_id=0, unit=S))
        info = getattr(rr, "information", {})
        t.ok(not rr.isError() and info == {0: b"modcp", 1: b"CP341-MODBUS", 2: a.modcp_version.encode()}
             and rr.conformity == 0x82,
             "FC43 basic: %r, conformity %r" % (info, getattr(rr, "conformity", None)))
        rr = c.execute(ReadDeviceInformationRequest(read_code=2, object_id=0, unit=S))
        info = getattr(rr, "information", {})
        t.ok(not rr.isError() and info.get(6) == b"manual example" and len(info) == 4,
             "FC43 regular: %r" % info)
        rr = c.execute(ReadDeviceInformationRequest(read_code=4, object_id=1, unit=S))
        info = getattr(rr, "information", {})
        t.ok(not rr.isError() and info == {1: b"CP341-MODBUS"}, "FC43 individual 01: %r" % info)
        rr = c.execute(ReadDeviceInformationRequest(read_code=4, object_id=3, unit=S))
        t.ok(isinstance(rr, ExceptionResponse) and rr.exception_code == 2,
             "FC43 individual 03 (not provided) -> 02")

        # -- comm-loss supervision ------------------------------------------------------------------
        t.ok(status().get("commloss") == "0", "comm loss: not armed by reads")
        rr = c.write_register(0x64, 0x1234, slave=S)
        t.ok(not rr.isError(), "FC06: arms the supervision")
        time.sleep(0.25)
        c.read_holding_registers(0x64, 1, slave=S)
        time.sleep(0.3)
        t.ok(status().get("commloss") == "0", "comm loss: 300 ms after a read, not lost")
        time.sleep(0.5)
        t.ok(status().get("commloss") == "1", "comm loss: 800 ms of silence -> commloss=1")
        t.ok("0E60" in sim.diag(), "comm loss: event (0E)60H in the diagnostic buffer")
        reg = diag(dm.ReturnDiagnosticRegisterRequest(unit=S))
        t.ok(reg == 0x0002, "FC08 02 diagnostic register with comm loss: %r (0002)" % reg)
        time.sleep(0.05)
        t.ok(status().get("commloss") == "1", "comm loss: latched through the next request ([ALTIVAR] §7)")
        sim.cmd("commloss reset")
        time.sleep(0.05)
        t.ok(status().get("commloss") == "0", "comm loss: cleared by the CPU side's reset")
    finally:
        try:
            c.close()
        except Exception:
            pass
        rc, gone = sim.stop()
        t.ok(rc == 0 and gone, "modcp-sim stopped cleanly (rc %s)" % rc)
    return t.done()


if __name__ == "__main__":
    sys.exit(main())
