//! Names of time directories, formatted as OpenFOAM's `Time::timeName` does.
//!
//! OpenFOAM writes a time with a C++ stream in the default ("general") float format and the
//! `timePrecision` of `system/controlDict` (default 6): that is C's `%.{precision}g`. So a run
//! writes `0`, `0.1`, `0.25`, `1e-05`, `100`, `1e+06`, and the accumulated round-off of
//! `0.1 + 0.2` still names the directory `0.3`.

/// OpenFOAM's default `timePrecision`.
pub const DEFAULT_TIME_PRECISION: usize = 6;

/// Directory name of time `t` with `precision` significant digits (`%.{precision}g`).
pub fn time_name(t: f64, precision: usize) -> String {
    format_general(t, precision)
}

/// C's `%.{precision}g`: with `X` the decimal exponent of `x` rounded to `P = max(precision, 1)`
/// significant digits, scientific notation (`1e-05`) when `X < -4` or `X ≥ P`, otherwise fixed
/// notation with `P − 1 − X` decimals; trailing zeros and a bare decimal point are removed.
/// The exponent has a sign and at least two digits, as C prints it.
pub fn format_general(x: f64, precision: usize) -> String {
    if x.is_nan() {
        return "nan".to_string();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf" } else { "-inf" }.to_string();
    }
    if x == 0.0 {
        // C prints "-0" for negative zero; a directory named "-0" would be a trap.
        return "0".to_string();
    }
    let significant = precision.max(1);
    // Rust's `{:e}` rounds to nearest exactly as C's `%e` does, so its exponent is C's X.
    let scientific = format!("{:.*e}", significant - 1, x);
    let (mantissa, exponent) = scientific
        .split_once('e')
        .expect("`{:e}` output always holds an exponent");
    let exponent: i32 = exponent.parse().expect("`{:e}` exponent is an integer");
    if exponent < -4 || exponent >= significant as i32 {
        let sign = if exponent < 0 { '-' } else { '+' };
        format!(
            "{}e{}{:02}",
            strip_trailing_zeros(mantissa),
            sign,
            exponent.unsigned_abs()
        )
    } else {
        let decimals = (significant as i32 - 1 - exponent) as usize;
        strip_trailing_zeros(&format!("{:.*}", decimals, x)).to_string()
    }
}

/// `"1.2500"` → `"1.25"`, `"3.000"` → `"3"`, `"100"` unchanged (no decimal point).
fn strip_trailing_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_match_c_general_format() {
        let p = DEFAULT_TIME_PRECISION;
        let cases: &[(f64, &str)] = &[
            (0.0, "0"),
            (-0.0, "0"),
            (0.1, "0.1"),
            (0.25, "0.25"),
            (1e-5, "1e-05"),
            (1e-4, "0.0001"),
            (100.0, "100"),
            (123456.0, "123456"),
            (1234567.0, "1.23457e+06"),
            (1e6, "1e+06"),
            (0.1 + 0.2, "0.3"),
            (2.5e-3, "0.0025"),
            (1.0 / 3.0, "0.333333"),
            (0.9999996, "1"),
            (99999.95, "99999.9"),
            (999999.5, "1e+06"),
            (-0.5, "-0.5"),
            (12.0, "12"),
            (0.000123456789, "0.000123457"),
        ];
        for &(t, expected) in cases {
            assert_eq!(time_name(t, p), expected, "time {t:e}");
        }
    }

    #[test]
    fn precision_changes_the_number_of_significant_digits() {
        assert_eq!(time_name(0.123456789, 3), "0.123");
        assert_eq!(time_name(0.123456789, 9), "0.123456789");
        assert_eq!(time_name(1234.0, 3), "1.23e+03");
        assert_eq!(time_name(1.6, 0), "2");
        assert_eq!(format_general(1e-300, 6), "1e-300");
        assert_eq!(format_general(f64::NAN, 6), "nan");
        assert_eq!(format_general(f64::NEG_INFINITY, 6), "-inf");
    }
}
