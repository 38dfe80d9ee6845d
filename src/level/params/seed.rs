//! A student's variant from their id: the same numbers for the same id and level file on every
//! machine (native and wasm), by two published algorithms another tool can redo in a few lines.
//!
//! 1. seed = FNV-1a, 64 bits (offset basis 0xcbf29ce484222325, prime 0x100000001b3), of the
//!    UTF-8 bytes of `FILE|ID`: FILE the level file's name without its folders
//!    (`incline_friction_param.ron`), ID the student id as given (spaces at its ends removed).
//! 2. SplitMix64 (Steele, Lea, Flood 2014) seeded with it: each call adds 0x9e3779b97f4a7c15 to
//!    the state and returns the state mixed by `z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9;
//!    z = (z ^ (z >> 27)) * 0x94d049bb133111eb; z ^ (z >> 31)` (wrapping u64 arithmetic).
//! 3. For each parameter in the order declared, one call: index = value mod n, n the number of
//!    its values (grid points min, min + step, ... up to max; or the list's length); the
//!    value is min + index * step (in f64) or the list's entry. The modulo's bias is below
//!    n / 2^64, nothing at classroom sizes.
//! 4. If at the values drawn one of the level's typical mistakes is within the question's
//!    student tolerance of its expected answer (the mistake could not be told from the right
//!    answer, and the variant does not validate), draw again: the same generator's next calls,
//!    one per parameter, as in 3. At most [`MAX_DRAWS`] draws; if each is such, the first (its
//!    error is then reported where the variant is made). A level whose mistakes are told apart
//!    at every value gives every student the first draw.

use super::decl::Parameter;

pub const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
pub const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// FNV-1a, 64 bits.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(FNV_OFFSET, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(FNV_PRIME)
    })
}

/// SplitMix64: a 64-bit state, one addition and a mix per number.
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
}

/// The text hashed for a student: `FILE|ID`.
pub fn seed_text(file_name: &str, id: &str) -> String {
    format!("{file_name}|{}", id.trim())
}

/// The most draws for one student (step 4): a quarter of the variants refused would leave a
/// student on a refused one after 16 draws once in 4^16, 4e9.
pub const MAX_DRAWS: usize = 16;

/// Each parameter's value index for student `id` of the level file named `file_name`: the
/// first draw (steps 1 to 3).
pub fn student_indices(file_name: &str, id: &str, params: &[Parameter]) -> Vec<u64> {
    student_draws(file_name, id, params)
        .next()
        .unwrap_or_default()
}

/// The draws of student `id` in order (steps 1 to 3, then 4's draws again), endless.
pub fn student_draws<'a>(
    file_name: &str,
    id: &str,
    params: &'a [Parameter],
) -> impl Iterator<Item = Vec<u64>> + 'a {
    let mut rng = SplitMix64(fnv1a64(seed_text(file_name, id).as_bytes()));
    std::iter::repeat_with(move || {
        params
            .iter()
            .map(|p| rng.next_u64() % p.values.count())
            .collect()
    })
}
