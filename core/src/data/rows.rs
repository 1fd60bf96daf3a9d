//! Row selections on the command line: lists of 1-based data-row numbers.

/// A list of 1-based data-row numbers, written like `1-20` or `1,10,12-14`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RowList(pub Vec<usize>);

impl std::str::FromStr for RowList {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        parse_row_list(text).map(RowList)
    }
}

/// Parses a list of 1-based row numbers such as `1-20` or `1,10,12-14`.
pub fn parse_row_list(text: &str) -> Result<Vec<usize>, String> {
    let mut rows = Vec::new();
    for part in text.split(',').map(str::trim) {
        rows.extend(parse_part(part)?);
    }
    Ok(rows)
}

/// One number or one range `first-last`.
fn parse_part(part: &str) -> Result<std::ops::RangeInclusive<usize>, String> {
    let number = |s: &str| s.trim().parse::<usize>().ok().filter(|&n| n > 0);
    let bad = || format!("{part:?} is not a row number or a range like 1-20 (rows count from 1)");
    let (first, last) = match part.split_once('-') {
        Some((first, last)) => (number(first).ok_or_else(bad)?, number(last).ok_or_else(bad)?),
        None => (number(part).ok_or_else(bad)?, number(part).ok_or_else(bad)?),
    };
    if first > last {
        return Err(bad());
    }
    Ok(first..=last)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn row_lists_take_numbers_and_ranges() {
        assert_eq!(parse_row_list("1-3,10"), Ok(vec![1, 2, 3, 10]));
        assert!(parse_row_list("0").is_err());
        assert!(parse_row_list("5-2").unwrap_err().contains("\"5-2\""));
        assert!(parse_row_list("x").is_err());
    }
}
