//! What the request and response readers and writers share.

use crate::canopen::{ObjectAddress, SdoAbortCode};

use super::data::{SdoInitiateData, SdoSegmentData};
use super::layout::{LAST, TOGGLE};
use super::view::{SdoFields, SdoFrame};

pub(super) fn abort_of(frame: &SdoFrame<&[u8]>) -> (ObjectAddress, SdoAbortCode) {
    (
        frame.multiplexer(),
        SdoAbortCode::new(u32::from_le_bytes(frame.data_field())),
    )
}

pub(super) fn initiate_fields<'a>(f: &mut SdoFields<'a>, data: &'a SdoInitiateData) {
    f.expedited = Some(data.is_expedited());
    f.size = Some(data.size());
    if data.is_expedited() {
        f.value = Some(data.data());
    }
}

pub(super) fn segment_command(
    specifier: u8,
    toggle: bool,
    data: &SdoSegmentData,
    last: bool,
) -> u8 {
    (specifier << 5)
        | if toggle { TOGGLE } else { 0 }
        | (data.unused() << 1)
        | if last { LAST } else { 0 }
}
