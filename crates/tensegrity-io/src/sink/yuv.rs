//! RGB → Y′CbCr 4:2:0 for video frames ([`rgb_to_yuv420`]): the BT.709 matrix (Kr = 0.2126,
//! Kb = 0.0722) in limited ("studio") range, 8 bits: Y′ = 16 + 219·E′y, Cb = 128 + 224·E′pb,
//! Cr = 128 + 224·E′pr with E′ the gamma-encoded (sRGB) components over 255, so white is Y′ 235,
//! black Y′ 16 and every grey has Cb = Cr = 128. Each chroma sample is the mean of a 2 × 2
//! block of pixels (centred between them, as MPEG-2/AV1 "unspecified/vertical" siting allows).
//!
//! 4:2:0 needs an even width and height: an odd width or height is padded with one white
//! column on the right or one white row at the bottom ([`even`]).

/// Y′CbCr 4:2:0 planes, 8 bits, row-major without padding.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Yuv420 {
    /// Width (even), pixels.
    pub width: usize,
    /// Height (even), pixels.
    pub height: usize,
    /// Luma, width × height.
    pub y: Vec<u8>,
    /// Cb, (width/2) × (height/2).
    pub u: Vec<u8>,
    /// Cr, (width/2) × (height/2).
    pub v: Vec<u8>,
}

/// The size rounded up to even numbers (the frame size of a video of `(w, h)` pictures).
pub fn even((w, h): (u32, u32)) -> (u32, u32) {
    (w + (w & 1), h + (h & 1))
}

const KR: f32 = 0.2126;
const KB: f32 = 0.0722;
const KG: f32 = 1.0 - KR - KB;

/// Luma of one RGB pixel (limited range).
fn luma(r: f32, g: f32, b: f32) -> f32 {
    16.0 + 219.0 / 255.0 * (KR * r + KG * g + KB * b)
}

/// Chroma (Cb, Cr) of one RGB colour (limited range).
fn chroma(r: f32, g: f32, b: f32) -> (f32, f32) {
    let y = KR * r + KG * g + KB * b;
    let cb = (b - y) / (2.0 * (1.0 - KB));
    let cr = (r - y) / (2.0 * (1.0 - KR));
    (128.0 + 224.0 / 255.0 * cb, 128.0 + 224.0 / 255.0 * cr)
}

fn byte(v: f32) -> u8 {
    v.round().clamp(0.0, 255.0) as u8
}

/// The RGB image (`rgb`: `w` × `h` pixels, 3 bytes each, row-major) as BT.709 limited-range
/// Y′CbCr 4:2:0, padded with white to an even size ([`even`]). An `rgb` shorter than
/// w × h × 3 is read as white where it ends.
pub fn rgb_to_yuv420(rgb: &[u8], (w, h): (u32, u32)) -> Yuv420 {
    let (w, h) = (w as usize, h as usize);
    let (ew, eh) = (w + (w & 1), h + (h & 1));
    let pixel = |x: usize, y: usize| -> [f32; 3] {
        if x >= w || y >= h {
            return [255.0; 3];
        }
        let i = 3 * (y * w + x);
        match rgb.get(i..i + 3) {
            Some(p) => [f32::from(p[0]), f32::from(p[1]), f32::from(p[2])],
            None => [255.0; 3],
        }
    };
    let mut y_plane = vec![0u8; ew * eh];
    let (cw, ch) = (ew / 2, eh / 2);
    let (mut u_plane, mut v_plane) = (vec![128u8; cw * ch], vec![128u8; cw * ch]);
    for by in 0..ch {
        for bx in 0..cw {
            let mut sum = [0.0f32; 3];
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let (x, y) = (2 * bx + dx, 2 * by + dy);
                let [r, g, b] = pixel(x, y);
                y_plane[y * ew + x] = byte(luma(r, g, b));
                sum = [sum[0] + r, sum[1] + g, sum[2] + b];
            }
            let (cb, cr) = chroma(sum[0] / 4.0, sum[1] / 4.0, sum[2] / 4.0);
            u_plane[by * cw + bx] = byte(cb);
            v_plane[by * cw + bx] = byte(cr);
        }
    }
    Yuv420 {
        width: ew,
        height: eh,
        y: y_plane,
        u: u_plane,
        v: v_plane,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn white_black_and_grey_map_to_the_limited_range_with_neutral_chroma() {
        for (grey, want) in [(255u8, 235u8), (0, 16), (128, 126)] {
            let yuv = rgb_to_yuv420(&[grey; 2 * 2 * 3], (2, 2));
            assert_eq!(yuv.y, vec![want; 4], "grey {grey}");
            assert_eq!(
                (yuv.u.as_slice(), yuv.v.as_slice()),
                (&[128][..], &[128][..])
            );
        }
    }

    #[test]
    fn primaries_follow_the_bt709_matrix() {
        // red: Y' = 16 + 219·0.2126, Cr at its top, Cb below neutral
        let red = rgb_to_yuv420(&[255, 0, 0].repeat(4), (2, 2));
        assert_eq!((red.y[0], red.u[0], red.v[0]), (63, 102, 240));
        let blue = rgb_to_yuv420(&[0, 0, 255].repeat(4), (2, 2));
        assert_eq!((blue.y[0], blue.u[0], blue.v[0]), (32, 240, 118));
    }

    #[test]
    fn an_odd_size_is_padded_with_white_and_chroma_averages_two_by_two() {
        assert_eq!(even((541, 400)), (542, 400));
        assert_eq!(even((3, 3)), (4, 4));
        // 3 × 1 black: padded to 4 × 2, the padding white
        let yuv = rgb_to_yuv420(&[0; 9], (3, 1));
        assert_eq!((yuv.width, yuv.height), (4, 2));
        assert_eq!(yuv.y, vec![16, 16, 16, 235, 235, 235, 235, 235]);
        // left block: two black over two white, a mid grey; still neutral
        assert_eq!((yuv.u, yuv.v), (vec![128, 128], vec![128, 128]));
    }
}
