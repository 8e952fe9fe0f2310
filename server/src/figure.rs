//! How the command line's tables and logs print a measured figure: four decimals,
//! or three significant digits in scientific notation below 1e-3 (an energy
//! balance of 3e-8 or a heat drift of 4e-9 would print as 0.0000).

/// `v` with four decimals, or as `1.23e-8` where it is nonzero and below 1e-3.
pub fn figure(v: f64) -> String {
    if v != 0.0 && v.abs() < 1e-3 { format!("{v:.2e}") } else { format!("{v:.4}") }
}

#[cfg(test)]
mod tests {
    use super::figure;

    #[test]
    fn small_figures_keep_their_digits() {
        assert_eq!(figure(0.0023), "0.0023");
        assert_eq!(figure(4.4e-9), "4.40e-9");
        assert_eq!(figure(0.0), "0.0000");
        assert_eq!(figure(-2.5e-5), "-2.50e-5");
        assert_eq!(figure(12.5), "12.5000");
    }
}
