//! The JSON keys of an SDO frame (SPEC §7.3): `sdo`, the frame as its
//! channel's tracker read it, and `transfer`, the transfer it ends. The
//! library's decoder reads; this file only writes what it says.

use std::io::{self, Write};

use motionwire::canopen::sdo::{SdoMultiplexer, SdoOutcome};
use motionwire::canopen::{object_name, ObjectSet};
use motionwire::decoder::{EndedTransfer, SdoStep};

use crate::json::{self, Object};

/// Write the `sdo` key's object for one frame (SPEC §7.3).
pub fn write_sdo_json<W: Write>(obj: &mut Object<'_, W>, step: &SdoStep<'_>) -> io::Result<()> {
    let out = obj.key("sdo")?;
    let mut o = Object::begin(out)?;
    o.name("direction", step.direction.name())?;
    o.name("service", step.service.name())?;
    let message = match &step.message {
        Ok(message) => message,
        Err(_) => {
            // A short frame: the multiplexer as far as it goes.
            if let Some(m) = step.multiplexer {
                write_multiplexer(&mut o, m, step.objects)?;
            }
            return o.end();
        }
    };
    let f = message.fields();
    if let Some(sub) = f.subcommand {
        o.name("subcommand", sub.name())?;
    }
    if let Some(m) = f.multiplexer {
        write_multiplexer(&mut o, m, step.objects)?;
    }
    if let Some(e) = f.expedited {
        o.bool("expedited", e)?;
    }
    if let Some(size) = f.size {
        match size {
            Some(size) => o.uint("size", u64::from(size))?,
            None => o.null("size")?,
        }
    }
    if let Some(value) = f.value {
        json::hex_string(o.key("value")?, value)?;
    }
    if let Some(t) = f.toggle {
        o.uint("toggle", u64::from(t))?;
    }
    if let Some(last) = f.last {
        o.bool("last", last)?;
    }
    if let Some(code) = f.abort_code {
        o.uint("abort_code", u64::from(code.get()))?;
        o.name("abort_description", code.description())?;
    }
    if let Some(crc) = f.crc_supported {
        o.bool("crc_supported", crc)?;
    }
    if let Some(b) = f.blksize {
        o.uint("blksize", u64::from(b))?;
    }
    if let Some(a) = f.ackseq {
        o.uint("ackseq", u64::from(a))?;
    }
    if let Some(s) = f.seqno {
        o.uint("seqno", u64::from(s))?;
    }
    if let Some(crc) = f.crc {
        o.uint("crc", u64::from(crc))?;
    }
    o.end()
}

fn write_multiplexer<W: Write>(
    o: &mut Object<'_, W>,
    m: SdoMultiplexer,
    objects: Option<ObjectSet>,
) -> io::Result<()> {
    o.uint("index", u64::from(m.index))?;
    o.uint("subindex", u64::from(m.subindex))?;
    match object_name(m.index, objects) {
        Some(name) => o.name("object", name),
        None => o.null("object"),
    }
}

/// Write the `transfer` key (SPEC §7.3).
pub fn write_transfer_json<W: Write>(
    obj: &mut Object<'_, W>,
    ended: &EndedTransfer<'_>,
    objects: Option<ObjectSet>,
) -> io::Result<()> {
    let transfer = &ended.transfer;
    let out = obj.key("transfer")?;
    let mut o = Object::begin(out)?;
    o.name("direction", transfer.direction.name())?;
    write_multiplexer(&mut o, transfer.multiplexer, objects)?;
    o.uint("size", u64::from(transfer.bytes))?;
    json::hex_string(o.key("data")?, ended.data)?;
    o.bool("truncated", ended.truncated())?;
    o.uint("frames", u64::from(transfer.frames))?;
    o.name("outcome", transfer.outcome.name())?;
    match transfer.outcome {
        SdoOutcome::Aborted { code, .. } => o.uint("abort_code", u64::from(code.get()))?,
        _ => o.null("abort_code")?,
    }
    match transfer.outcome {
        SdoOutcome::Broken(reason) => o.name("reason", reason.name())?,
        _ => o.null("reason")?,
    }
    o.uint("start_line", transfer.start_position)?;
    match transfer.duration {
        Some(d) => o.float("duration_ms", d.as_nanos() as f64 / 1e6)?,
        None => o.null("duration_ms")?,
    }
    o.end()
}
