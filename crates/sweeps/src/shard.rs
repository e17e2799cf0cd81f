//! Shards of a sweep: the cases one process runs (`--shard K/N`), so that a study can be
//! split over several processes or machines and the files merged ([`crate::merge()`]).

use crate::error::{Result, SweepError};
use std::str::FromStr;

/// The cases one process runs: ids ≡ `index` (mod `count`), i.e. `--shard K/N` with
/// `index` = K − 1 and `count` = N.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// K − 1.
    pub index: usize,
    /// N.
    pub count: usize,
}

impl Shard {
    /// Every case (`1/1`).
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// How many of `total` cases the shard runs.
    pub fn len(self, total: usize) -> usize {
        if self.index >= total {
            0
        } else {
            (total - self.index).div_ceil(self.count)
        }
    }

    /// Whether the shard runs no case of `total`.
    pub fn is_empty(self, total: usize) -> bool {
        self.len(total) == 0
    }

    /// The id of the shard's `j`-th case.
    pub fn id(self, j: usize) -> usize {
        self.index + j * self.count
    }
}

impl FromStr for Shard {
    type Err = SweepError;

    /// Parses `K/N` with 1 ≤ K ≤ N.
    ///
    /// ```
    /// use sweeps::Shard;
    /// assert_eq!("2/3".parse::<Shard>().unwrap(), Shard { index: 1, count: 3 });
    /// assert!("0/3".parse::<Shard>().is_err() && "4/3".parse::<Shard>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Shard> {
        let bad = |reason: &str| SweepError::InvalidShard {
            shard: s.to_string(),
            reason: reason.to_string(),
        };
        let (k, n) = s
            .split_once('/')
            .ok_or_else(|| bad("expected K/N, e.g. 2/4"))?;
        let k: usize = k
            .trim()
            .parse()
            .map_err(|_| bad("K is not a whole number"))?;
        let n: usize = n
            .trim()
            .parse()
            .map_err(|_| bad("N is not a whole number"))?;
        if n == 0 || k == 0 || k > n {
            return Err(bad("need 1 ≤ K ≤ N"));
        }
        Ok(Shard {
            index: k - 1,
            count: n,
        })
    }
}
