//! The EMCY producer state machine (docs/canopen.md#emcy-producer) and the
//! 1003h error history fed from its outcomes (docs/canopen.md#error-history),
//! driven by arbitrary event sequences.
//!
//! Input: a sequence of operations, an opcode byte (taken modulo 6) and its
//! payload, little-endian:
//!
//! | op | event | payload |
//! |---|---|---|
//! | 0 | `Initialised` | — |
//! | 1 | `ErrorOccurred`, register derived | code u16, manufacturer 5 bytes |
//! | 2 | `ErrorOccurred`, register supplied | code u16, register u8, manufacturer 5 bytes |
//! | 3 | `ErrorReset` | code u16 |
//! | 4 | `AllErrorsReset` | — |
//! | 5 | SDO write to 1003h | sub-index u8, value u32 |
//!
//! Each event goes to two producers, one with 2 slots (so that the capacity
//! overflow is reached) and one with the default 8, each checked against a
//! plain model of docs/canopen.md#emcy-producer, and each feeding its own
//! history (3 and the default 10 entries), checked against a model of
//! docs/canopen.md#error-history.
//!
//! Invariants after every step:
//! - exactly one of `transition` / `ignored` is set; an EMCY is sent exactly
//!   for transitions 1–4; the transition's target is the new condition;
//! - every EMCY's register has bit 0 set iff errors are active after the
//!   step, never the reserved bit 6, and equals the machine's register;
//! - error-free iff no error is active (tracked or untracked);
//! - reset EMCYs (transitions 2 and 4) have code 0x0000 and a zero
//!   manufacturer area; transition 4 register 0x00; error EMCYs carry the
//!   event's code and manufacturer bytes;
//! - the active errors are those of the model, in ascending code order,
//!   at most N of them; an overflow is reported exactly when the model has
//!   no free slot;
//! - `step` is pure: it leaves the state alone and agrees with `apply`;
//! - the history holds at most N entries, newest first, no reset codes;
//!   reads and writes of every sub-index never panic and answer as
//!   docs/canopen.md#error-history says.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::canopen::{
    Emcy, EmcyEvent, EmcyProducer, EmcyTransition, ErrorCode, ErrorCondition, ErrorHistory,
    ErrorRegister, IgnoredEvent, SdoAbortCode,
};
use motionwire_fuzz::Reader;

/// A fuzz step: a state-machine event or an SDO write to the history.
enum Op {
    Event(EmcyEvent),
    HistoryWrite { sub_index: u8, value: u32 },
}

fn next_op(input: &mut Reader) -> Option<Op> {
    Some(match input.u8()? % 6 {
        0 => Op::Event(EmcyEvent::Initialised),
        1 => {
            let code = ErrorCode::new(input.u16()?);
            Op::Event(EmcyEvent::error(code, input.array()?))
        }
        2 => {
            let code = ErrorCode::new(input.u16()?);
            let register = ErrorRegister::from_bits_retain(input.u8()?);
            Op::Event(EmcyEvent::error_with_register(
                code,
                register,
                input.array()?,
            ))
        }
        3 => Op::Event(EmcyEvent::reset(ErrorCode::new(input.u16()?))),
        4 => Op::Event(EmcyEvent::AllErrorsReset),
        _ => Op::HistoryWrite {
            sub_index: input.u8()?,
            value: input.u32()?,
        },
    })
}

fuzz_target!(|data: &[u8]| {
    let mut input = Reader::new(data);
    let mut small = Checked::<2, 3>::new();
    let mut default = Checked::<8, 10>::new();
    while let Some(op) = next_op(&mut input) {
        small.run(&op);
        default.run(&op);
    }
});

/// A producer with `N` slots and a history of `H` entries, with their models.
struct Checked<const N: usize, const H: usize> {
    producer: EmcyProducer<N>,
    history: ErrorHistory<H>,
    model: ProducerModel,
    /// The history as docs/canopen.md#error-history describes it: raw u32
    /// entries, newest first.
    history_model: Vec<u32>,
}

/// docs/canopen.md#emcy-producer as plainly as it can be written: the tracked
/// errors with their register contributions, and the bits of errors that found
/// no slot.
#[derive(Default)]
struct ProducerModel {
    tracked: Vec<(u16, u8)>,
    untracked: Option<u8>,
}

impl ProducerModel {
    fn error_free(&self) -> bool {
        self.tracked.is_empty() && self.untracked.is_none()
    }

    fn register(&self) -> u8 {
        if self.error_free() {
            return 0;
        }
        self.tracked
            .iter()
            .fold(1 | self.untracked.unwrap_or(0), |acc, &(_, bits)| {
                acc | bits
            })
    }
}

impl<const N: usize, const H: usize> Checked<N, H> {
    fn new() -> Self {
        Checked {
            producer: EmcyProducer::with_capacity(),
            history: ErrorHistory::with_capacity(),
            model: ProducerModel::default(),
            history_model: Vec::new(),
        }
    }

    fn run(&mut self, op: &Op) {
        match *op {
            Op::Event(event) => self.event(event),
            Op::HistoryWrite { sub_index, value } => self.history_write(sub_index, value),
        }
        self.check_history();
    }

    fn event(&mut self, event: EmcyEvent) {
        let before = self.producer;
        let (stepped, stepped_outcome) = before.step(event);
        assert_eq!(before, self.producer, "step changed the state it was given");
        let outcome = self.producer.apply(event);
        assert_eq!(
            (stepped, stepped_outcome),
            (self.producer, outcome),
            "step and apply differ"
        );

        let was_error_free = self.model.error_free();
        let expected = self.model_step(event);
        assert_eq!(outcome.transition(), expected.0, "{event:?}: {outcome:?}");
        assert_eq!(outcome.ignored(), expected.1, "{event:?}: {outcome:?}");
        assert_eq!(outcome.overflow(), expected.2, "{event:?}: {outcome:?}");

        // Exactly one of transition / ignored; an EMCY exactly for 1–4.
        assert_ne!(outcome.transition().is_some(), outcome.ignored().is_some());
        let sends = matches!(
            outcome.transition().map(EmcyTransition::number),
            Some(1..=4)
        );
        assert_eq!(outcome.emcy().is_some(), sends, "{outcome:?}");
        if outcome.ignored().is_some() {
            assert_eq!(self.producer, before, "an ignored event changed the state");
        }

        // Condition, register and active errors agree with the model.
        let producer = &self.producer;
        assert_eq!(producer.is_error_free(), self.model.error_free());
        assert_eq!(
            producer.condition() == ErrorCondition::ErrorFree,
            producer.active_count() == 0 && !producer.has_untracked_errors()
        );
        if let Some(transition) = outcome.transition() {
            assert_eq!(transition.target(), producer.condition());
            assert_eq!(
                EmcyTransition::from_number(transition.number()),
                Some(transition)
            );
        }
        assert_eq!(producer.error_register().bits(), self.model.register());
        assert!(!producer.error_register().contains(ErrorRegister::RESERVED));
        assert!(producer.active_count() <= N);
        let active: Vec<(u16, u8)> = producer
            .active_errors()
            .map(|error| (error.code().get(), error.register().bits()))
            .collect();
        assert_eq!(active, self.model.tracked);
        for &(code, _) in &self.model.tracked {
            assert!(producer.is_active(ErrorCode::new(code)));
        }

        if let Some(emcy) = outcome.emcy() {
            check_emcy(
                event,
                &emcy,
                outcome.transition(),
                producer.error_register(),
            );
            if !was_error_free {
                assert_ne!(outcome.transition(), Some(EmcyTransition::FirstError));
            }
        }

        // The history records error EMCYs only.
        let recorded = self.history.record_outcome(&outcome);
        match outcome.emcy() {
            Some(emcy) if !emcy.code.is_reset() => {
                assert!(recorded);
                let [a, b, ..] = emcy.manufacturer;
                let entry =
                    u32::from(emcy.code.get()) | u32::from(u16::from_le_bytes([a, b])) << 16;
                self.history_model.insert(0, entry);
                self.history_model.truncate(H);
            }
            _ => assert!(!recorded),
        }
    }

    /// Step the model; return (transition, ignored, overflow) as
    /// docs/canopen.md#emcy-producer and its rules say.
    fn model_step(
        &mut self,
        event: EmcyEvent,
    ) -> (
        Option<EmcyTransition>,
        Option<IgnoredEvent>,
        Option<ErrorCode>,
    ) {
        let model = &mut self.model;
        match event {
            EmcyEvent::Initialised => {
                *model = ProducerModel::default();
                (Some(EmcyTransition::Initialised), None, None)
            }
            EmcyEvent::AllErrorsReset => {
                if model.error_free() {
                    (None, Some(IgnoredEvent::AlreadyErrorFree), None)
                } else {
                    *model = ProducerModel::default();
                    (Some(EmcyTransition::AllErrorsReset), None, None)
                }
            }
            EmcyEvent::ErrorReset { code, .. } => {
                let Some(at) = model.tracked.iter().position(|&(c, _)| c == code.get()) else {
                    return (None, Some(IgnoredEvent::NotActive), None);
                };
                model.tracked.remove(at);
                if model.error_free() {
                    (Some(EmcyTransition::AllErrorsReset), None, None)
                } else {
                    (Some(EmcyTransition::ErrorReset), None, None)
                }
            }
            EmcyEvent::ErrorOccurred { code, register, .. } => {
                if code.get() >> 8 == 0 {
                    return (None, Some(IgnoredEvent::ResetCodeIsNotAnError), None);
                }
                if model.tracked.iter().any(|&(c, _)| c == code.get()) {
                    return (None, Some(IgnoredEvent::AlreadyActive), None);
                }
                let transition = if model.error_free() {
                    EmcyTransition::FirstError
                } else {
                    EmcyTransition::FurtherError
                };
                let bits = register.unwrap_or(code.register_class_bits()).bits() & !0x40;
                if model.tracked.len() < N {
                    model.tracked.push((code.get(), bits));
                    model.tracked.sort_unstable();
                    (Some(transition), None, None)
                } else {
                    model.untracked = Some(model.untracked.unwrap_or(0) | bits);
                    (Some(transition), None, Some(code))
                }
            }
        }
    }

    fn history_write(&mut self, sub_index: u8, value: u32) {
        let before = self.history;
        let result = self.history.write(sub_index, value);
        let expected = match (sub_index, value) {
            (0, 0) => Ok(()),
            (0, _) => Err(SdoAbortCode::INVALID_VALUE),
            _ if usize::from(sub_index) > H => Err(SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST),
            _ => Err(SdoAbortCode::WRITE_OF_READ_ONLY),
        };
        assert_eq!(
            result, expected,
            "write {value:#x} to 1003h sub {sub_index}"
        );
        match result {
            Ok(()) => self.history_model.clear(),
            Err(_) => assert_eq!(self.history, before, "a refused write changed the history"),
        }
    }

    fn check_history(&self) {
        let history = &self.history;
        assert!(history.len() <= H);
        assert_eq!(history.len(), self.history_model.len());
        assert_eq!(history.is_empty(), self.history_model.is_empty());
        assert_eq!(history.read(0), Ok(history.len() as u32));
        let entries: Vec<u32> = history.iter().map(|entry| entry.to_u32()).collect();
        assert_eq!(entries, self.history_model);
        assert_eq!(
            history.newest().map(|e| e.to_u32()),
            self.history_model.first().copied()
        );
        for entry in history.iter() {
            assert!(!entry.code.is_reset());
        }
        // Every sub-index that holds or may hold an entry, the first ones
        // that do not exist, and the largest.
        let last = u8::try_from(H + 2).unwrap_or(u8::MAX);
        for sub_index in (1..=last).chain([u8::MAX - 1, u8::MAX]) {
            let index = usize::from(sub_index);
            let expected = match self.history_model.get(index - 1) {
                Some(&entry) => Ok(entry),
                None if index <= H => Err(SdoAbortCode::NO_DATA_AVAILABLE),
                None => Err(SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST),
            };
            assert_eq!(
                history.read(sub_index),
                expected,
                "read 1003h sub {sub_index}"
            );
            assert_eq!(history.entry(sub_index).map(|e| e.to_u32()), expected.ok());
        }
    }
}

/// The EMCY a step sent, against the event and the register after the step.
fn check_emcy(
    event: EmcyEvent,
    emcy: &Emcy,
    transition: Option<EmcyTransition>,
    register_after: ErrorRegister,
) {
    // Bit 0 set iff errors are active after the step; never bit 6.
    assert_eq!(emcy.register, register_after);
    assert_eq!(
        emcy.register.contains(ErrorRegister::GENERIC),
        transition.map(EmcyTransition::target) == Some(ErrorCondition::ErrorOccurred)
    );
    assert!(!emcy.register.contains(ErrorRegister::RESERVED));
    match transition {
        Some(EmcyTransition::FirstError | EmcyTransition::FurtherError) => {
            let EmcyEvent::ErrorOccurred {
                code, manufacturer, ..
            } = event
            else {
                panic!("error EMCY for {event:?}");
            };
            assert_eq!(emcy.code, code);
            assert_eq!(emcy.manufacturer, manufacturer);
            assert!(!emcy.is_reset());
        }
        Some(EmcyTransition::ErrorReset | EmcyTransition::AllErrorsReset) => {
            assert_eq!(emcy.code, ErrorCode::NO_ERROR);
            assert_eq!(emcy.manufacturer, [0; 5]);
            if transition == Some(EmcyTransition::AllErrorsReset) {
                assert_eq!(emcy.register, ErrorRegister::empty());
            }
        }
        other => panic!("EMCY sent for {other:?}"),
    }
}
