//! A vertex coordinate written as decimal text (OBJ `v` lines, ASCII PLY), read the one way
//! every text loader reads it: Rust's `f32` parse (correctly rounded), with NaN and infinity
//! refused and a finite number beyond `f32`'s range told apart from them.

/// Why a coordinate token was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bad {
    /// Not a number at all.
    NotANumber,
    /// A finite decimal beyond `f32`'s range (it would round to infinity).
    OutOfRange,
    /// `nan`, `inf` or `infinity` written out.
    NonFinite,
}

impl Bad {
    /// What is wrong with `tok` and what to do (for [`Bad::NotANumber`] and
    /// [`Bad::OutOfRange`]; a NaN has its own error kind).
    pub fn message(self, tok: &str) -> String {
        match self {
            Bad::NotANumber => format!("bad vertex coordinate '{tok}'"),
            Bad::OutOfRange => format!(
                "coordinate {tok} is beyond the range of f32 (about -3.4e38 to 3.4e38); scale the model down"
            ),
            Bad::NonFinite => format!("coordinate {tok} is NaN or infinite"),
        }
    }
}

/// The finite `f32` nearest to the decimal `tok`.
pub fn parse(tok: &str) -> Result<f32, Bad> {
    let x = tok.parse::<f32>().map_err(|_| Bad::NotANumber)?;
    if x.is_finite() {
        Ok(x)
    } else if tok.parse::<f64>().is_ok_and(f64::is_finite) {
        Err(Bad::OutOfRange)
    } else {
        Err(Bad::NonFinite)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coordinates_are_read_or_refused_by_kind() {
        assert_eq!(parse("-1.5e2"), Ok(-150.0));
        assert_eq!(parse("x"), Err(Bad::NotANumber));
        assert_eq!(parse("1e39"), Err(Bad::OutOfRange));
        assert_eq!(parse("nan"), Err(Bad::NonFinite));
        assert_eq!(parse("-inf"), Err(Bad::NonFinite));
    }
}
