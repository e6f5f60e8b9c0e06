//! Strategies for the SDO frames (docs/canopen.md#sdo).

use proptest::prelude::*;

use crate::canopen::sdo::{
    SdoBlockSegment, SdoInitiateData, SdoRequest, SdoResponse, SdoSegmentData,
};
use crate::canopen::{ObjectAddress, SdoAbortCode};

/// Any multiplexer.
pub fn multiplexer() -> impl Strategy<Value = ObjectAddress> {
    (any::<u16>(), any::<u8>()).prop_map(|(index, subindex)| ObjectAddress::new(index, subindex))
}

/// Any initiate data, in the canonical form a frame reads back.
pub fn initiate_data() -> impl Strategy<Value = SdoInitiateData> {
    prop_oneof![
        proptest::collection::vec(any::<u8>(), 1..=4)
            .prop_map(|data| SdoInitiateData::expedited(&data).expect("1..=4 bytes")),
        any::<[u8; 4]>().prop_map(|bytes| SdoInitiateData::Expedited { bytes, len: None }),
        proptest::option::of(any::<u32>()).prop_map(|size| SdoInitiateData::Segmented { size }),
    ]
}

/// Any segment data, 0..=7 bytes.
pub fn segment_data() -> impl Strategy<Value = SdoSegmentData> {
    proptest::collection::vec(any::<u8>(), 0..=7)
        .prop_map(|data| SdoSegmentData::new(&data).expect("0..=7 bytes"))
}

fn abort_code() -> impl Strategy<Value = SdoAbortCode> {
    any::<u32>().prop_map(SdoAbortCode::new)
}

/// Any request.
pub fn request() -> impl Strategy<Value = SdoRequest> {
    prop_oneof![
        (multiplexer(), initiate_data())
            .prop_map(|(multiplexer, data)| SdoRequest::InitiateDownload { multiplexer, data }),
        (any::<bool>(), segment_data(), any::<bool>())
            .prop_map(|(toggle, data, last)| SdoRequest::DownloadSegment { toggle, data, last }),
        multiplexer().prop_map(|multiplexer| SdoRequest::InitiateUpload { multiplexer }),
        any::<bool>().prop_map(|toggle| SdoRequest::UploadSegment { toggle }),
        (multiplexer(), abort_code())
            .prop_map(|(multiplexer, code)| SdoRequest::Abort { multiplexer, code }),
        (multiplexer(), any::<bool>(), any::<u8>(), any::<u8>()).prop_map(
            |(multiplexer, crc_supported, blksize, pst)| SdoRequest::BlockUploadInitiate {
                multiplexer,
                crc_supported,
                blksize,
                pst,
            }
        ),
        Just(SdoRequest::BlockUploadEnd),
        (any::<u8>(), any::<u8>())
            .prop_map(|(ackseq, blksize)| SdoRequest::BlockUploadAck { ackseq, blksize }),
        Just(SdoRequest::BlockUploadStart),
        (
            multiplexer(),
            any::<bool>(),
            proptest::option::of(any::<u32>())
        )
            .prop_map(|(multiplexer, crc_supported, size)| {
                SdoRequest::BlockDownloadInitiate {
                    multiplexer,
                    crc_supported,
                    size,
                }
            }),
        (0u8..=7, any::<u16>())
            .prop_map(|(unused, crc)| SdoRequest::BlockDownloadEnd { unused, crc }),
    ]
}

/// Any response.
pub fn response() -> impl Strategy<Value = SdoResponse> {
    prop_oneof![
        (any::<bool>(), segment_data(), any::<bool>())
            .prop_map(|(toggle, data, last)| SdoResponse::UploadSegment { toggle, data, last }),
        any::<bool>().prop_map(|toggle| SdoResponse::DownloadSegment { toggle }),
        (multiplexer(), initiate_data())
            .prop_map(|(multiplexer, data)| SdoResponse::InitiateUpload { multiplexer, data }),
        multiplexer().prop_map(|multiplexer| SdoResponse::InitiateDownload { multiplexer }),
        (multiplexer(), abort_code())
            .prop_map(|(multiplexer, code)| SdoResponse::Abort { multiplexer, code }),
        (multiplexer(), any::<bool>(), any::<u8>()).prop_map(
            |(multiplexer, crc_supported, blksize)| SdoResponse::BlockDownloadInitiate {
                multiplexer,
                crc_supported,
                blksize,
            }
        ),
        Just(SdoResponse::BlockDownloadEnd),
        (any::<u8>(), any::<u8>())
            .prop_map(|(ackseq, blksize)| SdoResponse::BlockDownloadAck { ackseq, blksize }),
        (
            multiplexer(),
            any::<bool>(),
            proptest::option::of(any::<u32>())
        )
            .prop_map(|(multiplexer, crc_supported, size)| {
                SdoResponse::BlockUploadInitiate {
                    multiplexer,
                    crc_supported,
                    size,
                }
            }),
        (0u8..=7, any::<u16>())
            .prop_map(|(unused, crc)| SdoResponse::BlockUploadEnd { unused, crc }),
    ]
}

/// Any block segment with a sequence number of 1..=127.
pub fn block_segment() -> impl Strategy<Value = SdoBlockSegment> {
    (any::<bool>(), 1u8..=127, any::<[u8; 7]>()).prop_map(|(last, seqno, data)| SdoBlockSegment {
        last,
        seqno,
        data,
    })
}
