//! A render part's payload (`render::partial::decode_film`): pixel sums, then the denoiser's
//! guides when present. A payload that decodes must encode back to the same bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tracer_core::render::partial::{decode_film, encode_film};

fuzz_target!(|data: &[u8]| {
    if let Ok(film) = decode_film(data) {
        let again = encode_film(&film);
        assert_eq!(decode_film(&again).ok(), Some(film));
    }
});
