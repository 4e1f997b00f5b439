//! x86-64: SSE2 (part of the baseline) for the tiny-triangle rows.
//!
//! LLVM vectorises the rows' portable lane arrays by itself; these are the parts where it left
//! scalar code: the run's first pixel from the covered mask, the 5-6-5 colours of a row's eight
//! pixels, and the Gouraud channels' per-row arithmetic in one register.
#![allow(unsafe_code)]

use core::arch::x86_64::*;

use super::LANES;

/// The first lane whose mask is set (`LANES` if none): the lanes' sign bits in one `movemask`.
#[inline(always)]
pub(crate) fn first_covered(covered: [i16; LANES]) -> u32 {
    let c = covered;
    // SAFETY: SSE2 is part of the x86-64 baseline; no memory is accessed.
    let bits = unsafe {
        let v = _mm_set_epi16(c[7], c[6], c[5], c[4], c[3], c[2], c[1], c[0]);
        _mm_movemask_epi8(_mm_packs_epi16(v, v)) as u32 & 0xFF
    };
    (bits | 1 << LANES).trailing_zeros()
}

/// Up to four attribute values (32-bit, wrapping) in one register: a tiny triangle's row values,
/// stepped by a per-row step, and the offset of a row's first covered pixel from a table of
/// `step·column` for columns `0..=LANES`.
#[derive(Clone, Copy)]
pub(crate) struct ChannelRows<const N: usize> {
    value: __m128i,
    dy: __m128i,
    by_column: [__m128i; LANES + 1],
}

impl<const N: usize> ChannelRows<N> {
    /// Rows starting at `value`, stepped by `dx` per column and `dy` per row (`N ≤ 4`: the
    /// values past the fourth read as 0; `tiny::shade` takes no more).
    #[inline(always)]
    pub(crate) fn new(value: [u32; N], dx: [u32; N], dy: [u32; N]) -> Self {
        debug_assert!(N <= 4);
        let vector = |v: [u32; N]| {
            let w: [u32; 4] = core::array::from_fn(|k| v.get(k).copied().unwrap_or(0));
            // SAFETY: SSE2 is part of the x86-64 baseline.
            unsafe { _mm_setr_epi32(w[0] as i32, w[1] as i32, w[2] as i32, w[3] as i32) }
        };
        let (dx, mut next) = (vector(dx), vector([0; N]));
        let by_column = core::array::from_fn(|_| {
            let this = next;
            // SAFETY: as above.
            next = unsafe { _mm_add_epi32(next, dx) };
            this
        });
        ChannelRows {
            value: vector(value),
            dy: vector(dy),
            by_column,
        }
    }

    /// The values at `column` (at most `LANES`) of the current row; moves to the next row.
    #[inline(always)]
    pub(crate) fn next_row(&mut self, column: u32) -> [u32; N] {
        let mut out = [0u32; 4];
        // SAFETY: SSE2 is part of the x86-64 baseline; the store writes the 16 bytes of `out`.
        unsafe {
            let offset = self
                .by_column
                .get(column as usize)
                .copied()
                .unwrap_or(_mm_setzero_si128());
            _mm_storeu_si128(out.as_mut_ptr().cast(), _mm_add_epi32(self.value, offset));
            self.value = _mm_add_epi32(self.value, self.dy);
        }
        core::array::from_fn(|k| out.get(k).copied().unwrap_or(0))
    }
}

/// The raw 5-6-5 values of a row's eight pixels for the run from pixel `first`
/// (`color::packed565::row_565_portable` computes the same): the three channels' rounding to
/// their lanes and the first-pixel offset in one register (the lanes only matter modulo 2¹⁶),
/// then each channel's eight lanes. `start` and `lane` are in raw order (top, middle, bottom).
#[inline(always)]
pub(crate) fn row_565(start: [u32; 3], first: u32, lane: &[u32; 3]) -> [u16; LANES] {
    let mut raw = [0u16; LANES];
    // SAFETY: SSE2 is part of the x86-64 baseline; the one store writes the 16 bytes of `raw`.
    unsafe {
        let i32s = |v: [u32; 3]| _mm_setr_epi32(v[0] as i32, v[1] as i32, v[2] as i32, 0);
        // Lanes: (v + 2^12) >> 13 for the top and bottom channels, (v + 2^13) >> 14 for the
        // middle one (see `lanes`).
        let t = _mm_add_epi32(i32s(start), _mm_setr_epi32(1 << 12, 1 << 13, 1 << 12, 0));
        let (t13, t14) = (_mm_srli_epi32::<13>(t), _mm_srli_epi32::<14>(t));
        let middle = _mm_setr_epi32(0, -1, 0, 0);
        let lanes = _mm_or_si128(_mm_andnot_si128(middle, t13), _mm_and_si128(middle, t14));
        // Minus `first` steps, in the low 16 bits of each 32-bit lane.
        let steps = i32s(*lane);
        let at_zero = _mm_sub_epi16(lanes, _mm_mullo_epi16(steps, _mm_set1_epi16(first as i16)));
        // Each channel's value at pixel 0 in all eight lanes, plus i steps at pixel i.
        let index = _mm_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7);
        let top = _mm_unpacklo_epi64(
            _mm_shufflelo_epi16::<0x00>(at_zero),
            _mm_shufflelo_epi16::<0x00>(at_zero),
        );
        let mid = _mm_shufflelo_epi16::<0xAA>(at_zero);
        let mid = _mm_unpacklo_epi64(mid, mid);
        let bot = _mm_shufflehi_epi16::<0x00>(at_zero);
        let bot = _mm_unpackhi_epi64(bot, bot);
        let step = |k: usize| _mm_mullo_epi16(index, _mm_set1_epi16(lane[k] as i16));
        let top = _mm_add_epi16(top, step(0));
        let mid = _mm_add_epi16(mid, step(1));
        let bot = _mm_add_epi16(bot, step(2));
        let packed = _mm_or_si128(
            _mm_or_si128(
                _mm_and_si128(top, _mm_set1_epi16(0xF800u16 as i16)),
                _mm_and_si128(_mm_srli_epi16::<5>(mid), _mm_set1_epi16(0x07E0)),
            ),
            _mm_srli_epi16::<11>(bot),
        );
        _mm_storeu_si128(raw.as_mut_ptr().cast(), packed);
    }
    raw
}
