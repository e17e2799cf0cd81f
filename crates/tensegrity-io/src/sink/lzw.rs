//! The LZW coding of a GIF frame's colour indices ([`encode`]), written for figures: long
//! runs of one colour (the white page) cost a comparison per pixel instead of a dictionary
//! search.
//!
//! GIF's variable-width LZW (GIF89a, appendix F): with a minimum code size m, codes
//! 0 … 2^m − 1 are the indices themselves, 2^m clears the dictionary and 2^m + 1 ends the
//! data; each new code stands for an emitted string and the next index. Codes are written
//! least significant bit first, m + 1 bits wide to start; the width grows by one when the
//! decoder's next free code reaches 2^width (at most 12 bits, 4096 codes). The encoder here
//! tracks the decoder's next free code itself (it lags the encoder's by one code), so every
//! code is written at the width the decoder reads it with, and it clears the dictionary when
//! its own codes run out.
//!
//! The dictionary is a hash table of (string code, index) → code. A run of one index is
//! looked up through `run`: `run[k]` is the code of k + 1 copies of the run's index (known
//! since the last clear), so a run extends by direct indexing.

/// The largest code (GIF: 12 bits).
const MAX_CODES: u32 = 4096;
/// Slots of the hash table (a power of two, four times the codes: short probes).
const SLOTS: usize = 16384;

/// LZW-codes `indices` (every one below 2^`min_code_size`) as a GIF image's data: the
/// minimum code size byte, then the codes (without the sub-block framing).
///
/// ```
/// let data = [0u8, 0, 0, 1, 1, 0, 0, 0, 0];
/// let coded = tensegrity_io::sink::lzw::encode(&data, 2);
/// assert_eq!(coded[0], 2);
/// ```
pub fn encode(indices: &[u8], min_code_size: u8) -> Vec<u8> {
    let m = u32::from(min_code_size.clamp(2, 8));
    let clear = 1u32 << m;
    let end = clear + 1;
    let mut out = Vec::with_capacity(indices.len() / 4 + 16);
    out.push(m as u8);
    let mut bits = BitWriter::new(out);
    let mut dict = Dictionary::new(m);
    // the decoder's view: its next free code and the width it reads the next code with
    let mut decoder_next = end + 1;
    let mut width = m + 1;
    let mut first_after_clear = true;
    let mut emit = |bits: &mut BitWriter, code: u32, decoder_next: &mut u32, width: &mut u32| {
        bits.put(code, *width);
        if code == clear {
            *decoder_next = end + 1;
            *width = m + 1;
            first_after_clear = true;
            return;
        }
        if !first_after_clear && *decoder_next < MAX_CODES {
            *decoder_next += 1;
        }
        first_after_clear = false;
        if *decoder_next == 1 << *width && *width < 12 {
            *width += 1;
        }
    };
    emit(&mut bits, clear, &mut decoder_next, &mut width);
    let Some((&first, rest)) = indices.split_first() else {
        emit(&mut bits, end, &mut decoder_next, &mut width);
        return bits.finish();
    };
    let mut w = u32::from(first);
    // the current string is a run: its index and length - 1 (None once it is not)
    let mut run: Option<(u8, usize)> = Some((first, 0));
    let mut k = 0;
    while k < rest.len() {
        let c = rest[k];
        if let Some((r, len)) = run {
            if c == r {
                // extend the run as far as the dictionary knows it
                let known = dict.run_len(r);
                if len + 1 < known {
                    let more = rest[k..]
                        .iter()
                        .take(known - 1 - len)
                        .take_while(|&&x| x == r)
                        .count();
                    k += more;
                    w = dict.run_code(r, len + more);
                    run = Some((r, len + more));
                    continue;
                }
            }
        }
        match dict.find(w, c) {
            Some(code) => {
                w = code;
                run = None;
            }
            None => {
                emit(&mut bits, w, &mut decoder_next, &mut width);
                if dict.next < MAX_CODES {
                    let code = dict.add(w, c);
                    if let Some((r, len)) = run {
                        if c == r {
                            dict.extend_run(r, len + 1, code);
                        }
                    }
                }
                if dict.next == MAX_CODES {
                    emit(&mut bits, clear, &mut decoder_next, &mut width);
                    dict.reset();
                }
                w = u32::from(c);
                run = Some((c, 0));
            }
        }
        k += 1;
    }
    emit(&mut bits, w, &mut decoder_next, &mut width);
    emit(&mut bits, end, &mut decoder_next, &mut width);
    bits.finish()
}

/// The codes since the last clear: a hash table of (prefix, index) and the runs.
struct Dictionary {
    /// (prefix << 8 | index) + 1 per slot, 0 when empty.
    keys: Vec<u32>,
    codes: Vec<u16>,
    /// The next free code.
    next: u32,
    first_free: u32,
    /// Per index r: the codes of r repeated 1, 2, … times (the first is r itself).
    runs: Vec<Vec<u16>>,
}

impl Dictionary {
    fn new(m: u32) -> Self {
        let first_free = (1 << m) + 2;
        Self {
            keys: vec![0; SLOTS],
            codes: vec![0; SLOTS],
            next: first_free,
            first_free,
            runs: (0..256u16).map(|r| vec![r]).collect(),
        }
    }

    fn reset(&mut self) {
        self.keys.fill(0);
        self.next = self.first_free;
        for r in &mut self.runs {
            r.truncate(1);
        }
    }

    fn slot(key: u32) -> usize {
        (key.wrapping_mul(0x9E37_79B1) >> 18) as usize & (SLOTS - 1)
    }

    fn find(&self, w: u32, c: u8) -> Option<u32> {
        let key = (w << 8 | u32::from(c)) + 1;
        let mut s = Self::slot(key);
        loop {
            match self.keys[s] {
                0 => return None,
                k if k == key => return Some(u32::from(self.codes[s])),
                _ => s = (s + 1) & (SLOTS - 1),
            }
        }
    }

    fn add(&mut self, w: u32, c: u8) -> u32 {
        let key = (w << 8 | u32::from(c)) + 1;
        let mut s = Self::slot(key);
        while self.keys[s] != 0 {
            s = (s + 1) & (SLOTS - 1);
        }
        let code = self.next;
        self.keys[s] = key;
        self.codes[s] = code as u16;
        self.next += 1;
        code
    }

    /// How many repetitions of `r` have a code.
    fn run_len(&self, r: u8) -> usize {
        self.runs[usize::from(r)].len()
    }

    /// The code of `len + 1` repetitions of `r`.
    fn run_code(&self, r: u8, len: usize) -> u32 {
        u32::from(self.runs[usize::from(r)][len])
    }

    /// Records `code` as `len + 1` repetitions of `r` (the next length after those known).
    fn extend_run(&mut self, r: u8, len: usize, code: u32) {
        let run = &mut self.runs[usize::from(r)];
        if run.len() == len {
            run.push(code as u16);
        }
    }
}

/// Codes packed least significant bit first.
struct BitWriter {
    out: Vec<u8>,
    acc: u64,
    n: u32,
}

impl BitWriter {
    fn new(out: Vec<u8>) -> Self {
        Self { out, acc: 0, n: 0 }
    }

    fn put(&mut self, code: u32, width: u32) {
        self.acc |= u64::from(code) << self.n;
        self.n += width;
        while self.n >= 8 {
            self.out.push(self.acc as u8);
            self.acc >>= 8;
            self.n -= 8;
        }
    }

    fn finish(mut self) -> Vec<u8> {
        if self.n > 0 {
            self.out.push(self.acc as u8);
        }
        self.out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Decodes with the `gif` crate's decoder (weezl): an independent implementation.
    fn decoded(data: &[u8], min_code_size: u8) -> Vec<u8> {
        let w = data.len().min(500);
        let h = data.len() / w;
        let data = &data[..w * h];
        let (w, h) = (w as u16, h as u16);
        let mut frame = gif::Frame::from_indexed_pixels(w, h, vec![0; data.len()], None);
        frame.buffer = encode(data, min_code_size).into();
        let palette: Vec<u8> = (0..256u32).flat_map(|k| [k as u8, 0, 0]).collect();
        let mut file = Vec::new();
        {
            let mut e = gif::Encoder::new(&mut file, w, h, &palette).unwrap();
            e.write_lzw_pre_encoded_frame(&frame).unwrap();
        }
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::Indexed);
        let mut d = options.read_info(file.as_slice()).unwrap();
        let f = d.read_next_frame().unwrap().unwrap();
        f.buffer.to_vec()
    }

    fn lcg(seed: &mut u64) -> u64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        *seed >> 33
    }

    #[test]
    fn every_kind_of_data_decodes_to_itself() {
        let mut seed = 7;
        let mut cases: Vec<(Vec<u8>, u8)> = vec![
            (vec![3], 2),
            (vec![0; 100_000], 2),
            (vec![255; 70_000], 8),
            ((0..=255u8).cycle().take(60_000).collect(), 8),
        ];
        // random indices: the dictionary fills and clears many times
        cases.push(((0..50_000).map(|_| lcg(&mut seed) as u8).collect(), 8));
        cases.push(((0..50_000).map(|_| (lcg(&mut seed) % 4) as u8).collect(), 2));
        // runs of random lengths, as a figure's rows are
        let mut runs = Vec::new();
        while runs.len() < 200_000 {
            let c = (lcg(&mut seed) % 20) as u8;
            let n = 1 + (lcg(&mut seed) % 300) as usize;
            runs.extend(std::iter::repeat_n(c, n));
        }
        cases.push((runs, 5));
        for (data, m) in cases {
            let n = data.len() / data.len().min(500) * data.len().min(500);
            assert_eq!(
                decoded(&data, m),
                data[..n],
                "{} indices, m = {m}",
                data.len()
            );
        }
    }

    #[test]
    fn a_white_page_codes_to_a_few_bytes() {
        // a run of n costs about sqrt(2n) codes
        let coded = encode(&[0; 176_400], 8);
        assert!(coded.len() < 1000, "{} bytes", coded.len());
    }
}
