//! candump logs written by a real tool: python-can's `CanutilsLogWriter`
//! wrote `tests/fixtures/python_can.log` and python-can's
//! `CanutilsLogReader` read it back into `tests/fixtures/python_can.json`
//! (`scripts/gen_python_can_fixture.py`). The crate must read every frame as
//! python-can's own reader does.
//!
//! One documented difference (docs/formats.md#candump-log): python-can reads
//! its own error frame `(…) can0 20000080#0004000000000000` as an error frame
//! with identifier 0, no channel and no data; the crate keeps what the line
//! holds — the interface, the class bits (0x080, bus error) and the 8 data
//! bytes.

use motionwire::can::{FdFlags, Iface};
use motionwire::logs::candump;
use serde_json::Value;

#[test]
fn python_can_log_reads_as_python_can_reads_it() {
    let log = include_bytes!("../fixtures/python_can.log");
    let truth: Value = serde_json::from_str(include_str!("../fixtures/python_can.json")).unwrap();
    let expected = truth["frames"].as_array().unwrap();

    let frames: Vec<_> = candump::lines(log)
        .map(|(line, parsed)| {
            parsed
                .unwrap_or_else(|e| panic!("line {line}: {e}"))
                .unwrap_or_else(|| panic!("line {line}: no frame"))
        })
        .collect();
    assert_eq!(frames.len(), expected.len());

    for (i, (logged, want)) in frames.iter().zip(expected).enumerate() {
        let frame = &logged.frame;
        let ts = logged.timestamp.expect("python-can writes timestamps");
        assert_eq!(
            format!("{}.{:06}", ts.secs(), ts.micros()),
            want["timestamp"].as_str().unwrap(),
            "frame {i}"
        );
        assert_eq!(frame.is_error(), want["is_error_frame"], "frame {i}");
        if frame.is_error() {
            // python-can's reader drops an error frame's channel, class bits
            // and data; the line has them.
            assert_eq!(want["channel"], Value::Null);
            assert_eq!(logged.iface, Some(Iface::Name("can0")));
            assert_eq!(frame.id().raw(), 0x080);
            assert_eq!(frame.data(), [0, 0x04, 0, 0, 0, 0, 0, 0]);
            continue;
        }
        assert_eq!(
            logged.iface,
            Some(Iface::Name(want["channel"].as_str().unwrap())),
            "frame {i}"
        );
        assert_eq!(
            u64::from(frame.id().raw()),
            want["arbitration_id"],
            "frame {i}"
        );
        assert_eq!(frame.is_extended(), want["is_extended_id"], "frame {i}");
        assert_eq!(frame.is_rtr(), want["is_remote_frame"], "frame {i}");
        assert_eq!(frame.is_fd(), want["is_fd"], "frame {i}");
        assert_eq!(
            frame.fd_flags().contains(FdFlags::BRS),
            want["bitrate_switch"],
            "frame {i}"
        );
        assert_eq!(
            frame.fd_flags().contains(FdFlags::ESI),
            want["error_state_indicator"],
            "frame {i}"
        );
        // python-can's dlc is the data length for CAN FD and the requested
        // length for a remote request.
        let dlc = if frame.is_fd() {
            frame.data().len() as u64
        } else {
            u64::from(frame.dlc())
        };
        assert_eq!(dlc, want["dlc"], "frame {i}");
        let hex: String = frame.data().iter().map(|b| format!("{b:02x}")).collect();
        assert_eq!(hex, want["data"].as_str().unwrap(), "frame {i}");
    }
}
