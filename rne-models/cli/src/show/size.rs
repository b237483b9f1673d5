//! `--max-size`: a number of bytes, with an optional decimal suffix.

/// `300K` (300 000 bytes), `2M`, `1G`, or a plain number of bytes.
pub fn parse(text: &str) -> Result<usize, String> {
    let text = text.trim();
    let (digits, scale) = match text.char_indices().last() {
        Some((i, 'k' | 'K')) => (&text[..i], 1_000),
        Some((i, 'm' | 'M')) => (&text[..i], 1_000_000),
        Some((i, 'g' | 'G')) => (&text[..i], 1_000_000_000),
        _ => (text, 1),
    };
    digits
        .trim()
        .parse::<usize>()
        .ok()
        .and_then(|n| n.checked_mul(scale))
        .ok_or_else(|| {
            format!("'{text}' is not a size: expected bytes, or a number with K, M or G")
        })
}

#[cfg(test)]
mod tests {
    use super::parse;

    #[test]
    fn sizes_take_decimal_suffixes_and_refuse_anything_else() {
        assert_eq!(parse("300K"), Ok(300_000));
        assert_eq!(parse("2m"), Ok(2_000_000));
        assert_eq!(parse("812"), Ok(812));
        for bad in ["", "K", "1.5M", "-3", "12KB", "99999999999999999999G"] {
            assert!(parse(bad).is_err(), "{bad}");
        }
    }
}
