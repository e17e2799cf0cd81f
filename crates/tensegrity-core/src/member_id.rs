//! [`MemberId`]: a member named by kind and index within its kind.
//!
//! A leaf module (it imports nothing from the crate), so that both the model
//! ([`crate::structure`]) and the errors ([`crate::error`]) can name members without importing
//! each other. Members are numbered bars first, then strings; `MemberId::Bar(i)` is member `i`
//! and `MemberId::String(i)` is member `n_bars + i` (see
//! [`Structure::member_index`](crate::Structure::member_index)).

use std::fmt;

/// Identifies a member by kind and 0-based index within its kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MemberId {
    /// The i-th bar.
    Bar(usize),
    /// The i-th string.
    String(usize),
}

impl fmt::Display for MemberId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MemberId::Bar(i) => write!(f, "bar {i}"),
            MemberId::String(i) => write!(f, "string {i}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::MemberId;

    #[test]
    fn display_names_kind_and_index() {
        assert_eq!(MemberId::Bar(2).to_string(), "bar 2");
        assert_eq!(MemberId::String(0).to_string(), "string 0");
    }
}
