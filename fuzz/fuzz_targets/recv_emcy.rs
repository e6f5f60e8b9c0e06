//! The CiA 405 consumer (docs/canopen.md#recv-emcy): arbitrary sequences of
//! received EMCYs, `RECV_EMCY` / `RECV_EMCY_DEV` calls and configuration
//! changes.
//!
//! Input: a sequence of operations, an opcode byte (taken modulo 7) and its
//! payload. A node byte `n` names node `n % 8 + 1` when below 0x80 (so that
//! a few devices meet often) and `n % 127 + 1` otherwise; a code selector
//! byte picks 0x0000, 0x0001 (both resets), 0x8130, 0x4310 or, for 4..=255,
//! the frame's own bytes 0–1.
//!
//! | op | what | payload |
//! |---|---|---|
//! | 0 | device sends an EMCY | node, code selector, EMCY 8 bytes |
//! | 1 | `RECV_EMCY` call on block 0 or 1 | block byte |
//! | 2 | `RECV_EMCY` call, raw outputs | block byte |
//! | 3 | configure a device | node |
//! | 4 | unconfigure a device | node |
//! | 5 | `RECV_EMCY_DEV` for a device | node |
//! | 6 | a full scan without new EMCYs | block byte |
//!
//! Two `RecvEmcy` blocks scan the one storage, each checked against a model
//! of the scan docs/canopen.md#recv-emcy and the type's documentation describe
//! (ascending node-IDs from after the last delivered device, wrapping past
//! 127).
//!
//! Invariants:
//! - `receive` keeps the first error since the last reset (the root cause)
//!   and a reset always overwrites; `RECV_EMCY_DEV` returns exactly that
//!   error for a configured device, `NodeIdUnknown` for any other;
//! - a call delivers the device the model's scan finds: an error only for a
//!   configured device holding it, the device's root cause; a reset only
//!   once per delivered error — never two resets in a row for a device —
//!   and only for a configured device that now holds no error;
//! - DEVICE = 0 (all clear) only when no configured device holds an error
//!   and no reset is pending; with no device configured the call fails with
//!   `NodeIdUnknown`;
//! - the raw outputs agree with the typed result;
//! - with the storage unchanged, a full scan delivers every configured
//!   device in error, and ends in "all clear" once no device is in error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::canopen::{
    Emcy, EmcyStorage, ErrorCode, KernelError, NodeId, RecvEmcy, RecvEmcyOutputs, RecvEmcyResult,
    SlotUpdate,
};
use motionwire_fuzz::Reader;

fn node(raw: u8) -> NodeId {
    let id = if raw < 0x80 {
        raw % 8 + 1
    } else {
        raw % 127 + 1
    };
    NodeId::new(id).expect("1..=127")
}

fn code(selector: u8, frame: [u8; 8]) -> ErrorCode {
    match selector {
        0 => ErrorCode::new(0x0000),
        1 => ErrorCode::new(0x0001),
        2 => ErrorCode::LIFE_GUARD,
        3 => ErrorCode::new(0x4310),
        _ => ErrorCode::new(u16::from_le_bytes([frame[0], frame[1]])),
    }
}

/// What the model knows: per device the root cause, which devices are
/// configured, and per block where its scan continues and which devices it
/// last delivered with an error.
struct Model {
    root_cause: [Option<Emcy>; 128],
    configured: [bool; 128],
    blocks: [BlockModel; 2],
}

#[derive(Clone, Copy)]
struct BlockModel {
    next: u8,
    /// Per device: the block's last delivery for it was an error.
    error_delivered: [bool; 128],
}

impl Model {
    fn any_configured(&self) -> bool {
        self.configured.iter().any(|&c| c)
    }

    /// The scan of docs/canopen.md#recv-emcy: the first configured device from
    /// `next` on, wrapping past 127, that holds an error or whose error was
    /// delivered.
    fn scan(&self, block: usize) -> Option<u8> {
        let b = &self.blocks[block];
        (0..127u8)
            .map(|offset| (b.next - 1 + offset) % 127 + 1)
            .find(|&id| {
                let i = usize::from(id);
                self.configured[i] && (self.root_cause[i].is_some() || b.error_delivered[i])
            })
    }
}

struct Fixture {
    storage: EmcyStorage,
    blocks: [RecvEmcy; 2],
    model: Model,
}

fuzz_target!(|data: &[u8]| {
    let mut input = Reader::new(data);
    let mut f = Fixture {
        storage: EmcyStorage::new(),
        blocks: [RecvEmcy::new(), RecvEmcy::new()],
        model: Model {
            root_cause: [None; 128],
            configured: [false; 128],
            blocks: [BlockModel {
                next: 1,
                error_delivered: [false; 128],
            }; 2],
        },
    };
    while let Some(op) = input.u8() {
        let done = match op % 7 {
            0 => (|| {
                let node = node(input.u8()?);
                let selector = input.u8()?;
                let frame: [u8; 8] = input.array()?;
                let mut emcy = Emcy::from_bytes(&frame);
                emcy.code = code(selector, frame);
                f.receive(node, emcy);
                Some(())
            })(),
            1 => input.u8().map(|b| {
                let _ = f.call(usize::from(b & 1), false);
            }),
            2 => input.u8().map(|b| {
                let _ = f.call(usize::from(b & 1), true);
            }),
            3 => input.u8().map(|n| f.configure(node(n), true)),
            4 => input.u8().map(|n| f.configure(node(n), false)),
            5 => input.u8().map(|n| f.recv_emcy_dev(node(n))),
            _ => input.u8().map(|b| f.full_scan(usize::from(b & 1))),
        };
        if done.is_none() {
            break;
        }
        f.check_storage();
    }
});

impl Fixture {
    fn receive(&mut self, node: NodeId, emcy: Emcy) {
        let i = usize::from(node.get());
        let held = self.model.root_cause[i];
        let update = self.storage.receive(node, emcy);
        if emcy.is_reset() {
            assert_eq!(update, SlotUpdate::Reset { cleared: held });
            self.model.root_cause[i] = None;
            assert_eq!(self.storage.slot(node), emcy, "a reset always overwrites");
        } else {
            match held {
                None => {
                    assert_eq!(update, SlotUpdate::RootCause);
                    self.model.root_cause[i] = Some(emcy);
                }
                Some(root_cause) => assert_eq!(update, SlotUpdate::FollowUp { root_cause }),
            }
        }
    }

    fn configure(&mut self, node: NodeId, configured: bool) {
        let i = usize::from(node.get());
        let changed = if configured {
            self.storage.add_device(node)
        } else {
            self.storage.remove_device(node)
        };
        assert_eq!(changed, self.model.configured[i] != configured);
        self.model.configured[i] = configured;
    }

    fn recv_emcy_dev(&mut self, node: NodeId) {
        let i = usize::from(node.get());
        let result = self.storage.recv_emcy_dev(node);
        let outputs = self.storage.recv_emcy_dev_outputs(node);
        if self.model.configured[i] {
            // The first error since the last reset, on every call.
            assert_eq!(result, Ok(self.model.root_cause[i]));
            assert!(outputs.confirm());
            assert_eq!(outputs.error(), KernelError::NoError);
            match self.model.root_cause[i] {
                Some(error) => assert_eq!(outputs.errorinfo(), error),
                None => assert_eq!(outputs.errorinfo().code, ErrorCode::NO_ERROR),
            }
            assert_eq!(
                outputs.emergency_received(),
                self.model.root_cause[i].is_some()
            );
        } else {
            assert_eq!(result, Err(KernelError::NodeIdUnknown));
            assert!(!outputs.confirm());
            assert_eq!(outputs.error(), KernelError::NodeIdUnknown);
            assert_eq!(outputs.errorinfo(), Emcy::from_bytes(&[0; 8]));
        }
    }

    /// One `RECV_EMCY` call on `block`, checked against the model; returns
    /// the typed result.
    fn call(&mut self, block: usize, raw: bool) -> Result<RecvEmcyResult, KernelError> {
        let mut twin = self.blocks[block];
        let result = self.blocks[block].call(&self.storage);
        if raw {
            // The raw outputs of the same call agree with the typed result.
            let outputs = twin.call_outputs(&self.storage);
            assert_eq!(twin, self.blocks[block]);
            assert_eq!(outputs, RecvEmcyOutputs::from(result));
            assert_eq!(outputs.confirm(), result.is_ok());
            assert_eq!(
                outputs.device(),
                result.ok().and_then(|r| r.device()).map_or(0, NodeId::get)
            );
            assert_eq!(
                outputs.emergency_received(),
                matches!(result, Ok(RecvEmcyResult::Error { .. }))
            );
        }

        if !self.model.any_configured() {
            assert_eq!(result, Err(KernelError::NodeIdUnknown));
            return result;
        }
        let expected = self.model.scan(block);
        let model = &mut self.model;
        match result {
            Err(error) => panic!("call failed with {error:?} while devices are configured"),
            Ok(RecvEmcyResult::AllClear) => {
                assert_eq!(expected, None, "all clear while device {expected:?} is due");
                // DEVICE = 0 only when no configured device holds an error.
                for id in 1..=127usize {
                    assert!(!(model.configured[id] && model.root_cause[id].is_some()));
                    assert!(!(model.configured[id] && model.blocks[block].error_delivered[id]));
                }
            }
            Ok(RecvEmcyResult::Error { device, emcy }) => {
                let i = usize::from(device.get());
                assert_eq!(Some(device.get()), expected);
                assert!(model.configured[i]);
                assert_eq!(Some(emcy), model.root_cause[i], "not the root cause");
                model.blocks[block].error_delivered[i] = true;
                model.blocks[block].next = device.get() % 127 + 1;
            }
            Ok(RecvEmcyResult::ResetError { device, reset }) => {
                let i = usize::from(device.get());
                assert_eq!(Some(device.get()), expected);
                assert!(model.configured[i]);
                assert!(model.root_cause[i].is_none());
                assert!(reset.is_reset());
                assert_eq!(reset, self.storage.slot(device));
                // Only after an error was delivered: never two in a row.
                assert!(
                    model.blocks[block].error_delivered[i],
                    "second reset in a row for {device}"
                );
                model.blocks[block].error_delivered[i] = false;
                model.blocks[block].next = device.get() % 127 + 1;
            }
        }
        result
    }

    /// With the storage unchanged, as many calls as there are configured
    /// devices deliver every configured device in error; once none is in
    /// error, one more round ends in "all clear".
    fn full_scan(&mut self, block: usize) {
        let configured = self.model.configured.iter().filter(|&&c| c).count();
        if configured == 0 {
            assert_eq!(self.call(block, false), Err(KernelError::NodeIdUnknown));
            return;
        }
        let in_error: Vec<u8> = (1..=127u8)
            .filter(|&id| {
                let i = usize::from(id);
                self.model.configured[i] && self.model.root_cause[i].is_some()
            })
            .collect();
        let mut delivered = Vec::new();
        let mut all_clear = false;
        for _ in 0..configured {
            match self.call(block, false) {
                Ok(RecvEmcyResult::Error { device, .. }) => delivered.push(device.get()),
                Ok(RecvEmcyResult::AllClear) => all_clear = true,
                _ => {}
            }
        }
        for id in &in_error {
            assert!(
                delivered.contains(id),
                "device {id} in error not delivered by a full scan"
            );
        }
        if in_error.is_empty() {
            if !all_clear {
                // Pending resets are all delivered by now.
                assert_eq!(self.call(block, false), Ok(RecvEmcyResult::AllClear));
            }
        } else {
            assert!(!all_clear, "all clear while devices are in error");
        }
    }

    fn check_storage(&self) {
        let mut in_error = 0;
        for node in NodeId::all() {
            let i = usize::from(node.get());
            assert_eq!(self.storage.root_cause(node), self.model.root_cause[i]);
            assert_eq!(self.storage.is_configured(node), self.model.configured[i]);
            assert_eq!(
                self.storage.devices_in_error().contains(node),
                self.model.root_cause[i].is_some()
            );
            in_error += usize::from(self.model.root_cause[i].is_some());
        }
        assert_eq!(self.storage.devices_in_error().len(), in_error);
    }
}
