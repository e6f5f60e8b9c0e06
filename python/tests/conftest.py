"""What the tests of the Python package share: the repository's paths, the
program's output snapshot (tests/golden), and python-can as the oracle of
the log readers, with the differences docs/formats.md#where-tools-disagree
lists written out as rules."""

from __future__ import annotations

import gzip
import shlex
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "tests" / "fixtures"
SAMPLE = ROOT / "samples" / "machine.log"


def golden_name(line: str) -> str:
    """The snapshot's file name for a case of tests/golden/cases.txt: the
    arguments joined by `_`, `tests/fixtures/` left out and every other `/`
    and every `:` written `-` (`golden_name` in tests/common/mod.rs)."""
    name = "_".join(line.split()).replace("tests/fixtures/", "")
    return name.replace("/", "-").replace(":", "-") + ".gz"


def golden_cases() -> list[tuple[str, list[str]]]:
    """The program's command lines of tests/golden/cases.txt, each with its
    snapshot's file name."""
    lines = (ROOT / "tests" / "golden" / "cases.txt").read_text().splitlines()
    return [(golden_name(line), shlex.split(line)) for line in lines]


def golden_stdout(name: str) -> str:
    """The program's standard output in the snapshot `name` (status, stderr
    length, stderr, stdout)."""
    text = gzip.decompress((ROOT / "tests" / "golden" / name).read_bytes()).decode()
    _status, rest = text.split("\n", 1)
    length_line, rest = rest.split("\n", 1)
    length = int(length_line.removeprefix("stderr "))
    return rest.encode()[length:].decode()


def decode_options(args: list[str]) -> tuple[dict, str] | None:
    """The keyword arguments of motionwire.decode/summary for the program's
    `decode` options, and the file; None for options the package has no
    counterpart of (filters, renderings)."""
    kwargs: dict = {}
    files = []
    words = iter(args[1:])
    for word in words:
        if word in ("--json", "--summary"):
            continue
        if word == "--heartbeat-ms":
            kwargs["heartbeat_ms"] = int(next(words))
        elif word == "--profile":
            profiles: dict = {}
            for item in next(words).split(","):
                node, _, name = item.rpartition("=")
                profiles[int(node) if node else None] = name
            kwargs["profiles"] = profiles
        elif word == "--eds":
            node, _, path = next(words).partition("=")
            kwargs.setdefault("eds", {})[int(node)] = str(ROOT / path)
        elif word.startswith("-"):
            return None
        else:
            files.append(word)
    if len(files) != 1:
        return None
    return kwargs, str(ROOT / files[0])


# ---------------------------------------------------------------------------
# python-can as the oracle (docs/formats.md#where-tools-disagree)

#: The files python-can's can.LogReader reads, by suffix, in the fixtures
#: and the sample.
PYTHON_CAN_SUFFIXES = (".log", ".asc", ".blf", ".trc", ".mf4")


def python_can_files() -> list[Path]:
    files = sorted(p for p in FIXTURES.rglob("*") if p.suffix in PYTHON_CAN_SUFFIXES)
    return files + [SAMPLE]


def frame_of_row(row: dict) -> dict:
    """A row of read_log as the comparison reads it."""
    return {
        "ts": row["ts"],
        "channel": row["iface"],
        "id": row["id"],
        "extended": row["extended"],
        "rtr": row["rtr"],
        "fd": row["fd"],
        "brs": row["brs"],
        "esi": row["esi"],
        "error": row["error"],
        # read_log's dlc is the code (ISO 11898-1) for CAN FD; python-can's
        # is the length.
        "length": len(row["data"]) if row["fd"] else row["dlc"],
        "data": bytes(row["data"]),
        "rx": None,
    }


def frame_of_message(msg) -> dict:
    """A can.Message (python-can's, or one motionwire.Reader made) as the
    comparison reads it."""
    return {
        "ts": msg.timestamp,
        "channel": None if msg.channel is None else str(msg.channel),
        "id": msg.arbitration_id,
        "extended": msg.is_extended_id,
        "rtr": msg.is_remote_frame,
        "fd": msg.is_fd,
        "brs": msg.bitrate_switch,
        "esi": msg.error_state_indicator,
        "error": msg.is_error_frame,
        "length": msg.dlc,
        "data": bytes(msg.data),
        "rx": msg.is_rx,
    }


#: CAN FD lengths by DLC code (ISO 11898-1).
DLC_LENGTHS = [0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64]


class Oracle:
    """What python-can's reading of a file says motionwire's must be, rule by
    rule (each rule a row of docs/formats.md#where-tools-disagree)."""

    def __init__(self, path: Path):
        self.path = path
        self.suffix = path.suffix
        head = path.read_bytes()[:4096]
        self.text = head.decode("latin-1")
        # ASC `timestamps relative`: python-can (4.6) gives the times as
        # written; motionwire adds them up (seconds since the start).
        self.relative_asc = self.suffix == ".asc" and "timestamps relative" in self.text
        # TRC without a bus column: python-can says channel 1; motionwire
        # names no interface.
        # (docs/formats.md#trc: versions 1.2 and 1.3, and 2.x with `B`).
        compact = self.text.replace(" ", "")
        self.trc_bus = (
            "$FILEVERSION=1.2" in compact
            or "$FILEVERSION=1.3" in compact
            or ("$COLUMNS=" in compact and ",B," in compact)
        )

    def python_can_only(self) -> int:
        """How many python-can messages motionwire does not read: ASC `TxRq`
        lines (a transmit request, skipped as asc2log skips it)."""
        if self.suffix != ".asc":
            return 0
        return sum(1 for line in self.path.read_text(errors="replace").splitlines() if " TxRq " in line)

    def motionwire_only(self, frame: dict) -> bool:
        """A frame python-can does not read: TRC `ER` rows (python-can skips
        them; motionwire reads error frames)."""
        return self.suffix == ".trc" and frame["error"]

    def differences(self, ours: dict, theirs: dict) -> list[str]:
        """The fields in which `ours` differs from what `theirs` (python-can's
        reading) and the documented rules make it."""
        out = []

        def check(key, expected, found):
            if expected != found:
                out.append(f"{key}: python-can {expected!r}, motionwire {found!r}")

        if not self.relative_asc:
            ts = ours["ts"] if ours["ts"] is not None else 0.0
            if abs(ts - theirs["ts"]) > 1.5e-6:
                out.append(f"ts: python-can {theirs['ts']!r}, motionwire {ours['ts']!r}")
        check("error", theirs["error"], ours["error"])
        if not (theirs["error"] and self.suffix == ".log"):
            # candump: python-can drops an error frame's channel.
            check("channel", self.channel(theirs), ours["channel"])
        if ours["error"]:
            # Error frames: python-can gives identifier 0 and no data (candump,
            # ASC), or the object's / record's identifier and data (BLF
            # CAN_ERROR_EXT, MF4 CAN_ErrorFrame); motionwire the class bits
            # and Linux's layout of the error.
            return out
        check("id", theirs["id"], ours["id"])
        check("extended", theirs["extended"], ours["extended"])
        fd, rtr = theirs["fd"], theirs["rtr"]
        if self.suffix == ".asc" and fd and not ours["fd"] and len(ours["data"]) <= 8:
            # ASC: a CANFD line without EDL of at most 8 bytes is a classic
            # frame, a remote request when its flags have 0x10 (asc2log);
            # python-can marks every CANFD line as CAN FD, and one of length
            # 0 as a remote request (docs/formats.md#asc).
            fd = False
            if not theirs["data"]:
                rtr = ours["rtr"]
        theirs_data, length = theirs["data"], theirs["length"]
        if self.suffix == ".asc" and not theirs["fd"] and theirs["length"] > 8:
            # ASC: a classic line whose DLC code is above 8. Followed by its
            # CAN FD length of bytes it is a CAN FD frame, python-can keeps 8
            # of them and reads it classic; followed by 8 it is a classic
            # frame of 8, python-can gives the code's length
            # (docs/formats.md#asc; the disagreements' table).
            if ours["fd"] and ours["data"][:8] == theirs_data:
                fd, theirs_data, length = True, ours["data"], len(ours["data"])
            elif not ours["fd"] and len(theirs_data) == 8:
                length = 8
        check("rtr", rtr, ours["rtr"])
        check("fd", fd, ours["fd"])
        brs = theirs["brs"]
        if self.suffix == ".trc" and theirs["esi"]:
            # TRC FE and BI: FE is ESI, BI is BRS and ESI (PEAK);
            # python-can: BRS for FE, not for BI.
            brs = not brs
        if fd:
            check("brs", brs, ours["brs"])
            check("esi", theirs["esi"], ours["esi"])
        if not ours["rtr"]:
            check("data", theirs_data, ours["data"])
        if self.suffix == ".trc" and theirs["fd"]:
            # python-can's TRCReader gives a CAN FD frame's DLC code as its
            # dlc (9 for 12 bytes), its other readers the length.
            length = DLC_LENGTHS[length]
        check("length", length, ours["length"])
        if ours["rx"] is not None:
            check("rx", theirs["rx"], ours["rx"])
        return out

    def channel(self, theirs: dict):
        channel = theirs["channel"]
        if self.suffix in (".asc", ".blf") and channel is not None:
            # ASC, BLF: python-can counts channels from 0; motionwire keeps
            # the file's numbers, from 1.
            return str(int(channel) + 1)
        if self.suffix == ".trc" and not self.trc_bus:
            return None
        return channel


def compare(path: Path, ours: list[dict], theirs: list[dict]) -> list[str]:
    """Pair motionwire's frames with python-can's in order, skipping only
    what the rules allow, and list every difference."""
    oracle = Oracle(path)
    allowed_skips = oracle.python_can_only()
    problems: list[str] = []
    i = j = 0
    skipped_theirs = 0
    while i < len(ours) or j < len(theirs):
        if i < len(ours) and oracle.motionwire_only(ours[i]):
            i += 1
            continue
        if i >= len(ours) or j >= len(theirs):
            problems.append(f"{len(ours) - i} of ours and {len(theirs) - j} of python-can's left over")
            break
        found = oracle.differences(ours[i], theirs[j])
        if found and skipped_theirs < allowed_skips:
            skipped_theirs += 1
            j += 1
            continue
        if found:
            problems.append(f"frame {i} (python-can's {j}): " + "; ".join(found))
        i += 1
        j += 1
    if skipped_theirs != allowed_skips:
        problems.append(f"python-can's TxRq frames: {allowed_skips} expected, {skipped_theirs} skipped")
    return problems
