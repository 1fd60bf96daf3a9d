//! One printed line taken apart: the record prefix a sketch puts first (`a/g:`, `Raw:`, a tuple's
//! parenthesis), then either numbers or `label:value` pairs, separated by commas, tabs, spaces or
//! semicolons. Nothing here knows which dialect a line belongs to; [`super::dialect`] decides.

/// The parts of one line.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Fields {
    /// The record prefix (`a/g`, `Raw`, `Uni`, `()` for a tuple), when the line has one.
    pub prefix: Option<String>,
    /// The labels of `label:value` pairs, in order; empty for a line of bare numbers.
    pub labels: Vec<String>,
    /// The values, in order.
    pub values: Vec<f64>,
    /// The separator between values was a comma (a CSV), rather than white space.
    pub commas: bool,
}

/// What a line that holds no numbers to take holds.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Words {
    /// Words only, split as a header would be: `millis,ax,ay,...`.
    Header(Vec<String>),
    /// Anything else: a banner, a boot message, a prompt.
    Text,
}

/// Record prefixes that sketches print before a line's numbers.
const PREFIXES: [&str; 5] = ["a/g:", "Raw:", "Uni:", "Cal1:", "Cal2:"];

/// The fields of `line`, or what it holds instead.
pub(super) fn fields(line: &str) -> Result<Fields, Words> {
    let line = line.trim_matches(|c: char| c.is_whitespace() || c == '\0');
    let (prefix, body) = split_prefix(line);
    let commas = body.contains(',');
    let tokens: Vec<&str> = body.split([',', '\t', ' ', ';']).filter(|t| !t.is_empty()).collect();
    let mut parsed = Fields { prefix, labels: Vec::new(), values: Vec::new(), commas };
    for token in &tokens {
        if !take(&mut parsed, token) {
            return Err(words(&tokens));
        }
    }
    match parsed.values.is_empty() || (!parsed.labels.is_empty() && parsed.labels.len() != parsed.values.len()) {
        true => Err(words(&tokens)),
        false => Ok(parsed),
    }
}

fn split_prefix(line: &str) -> (Option<String>, &str) {
    if let Some(prefix) = PREFIXES.iter().find(|p| line.starts_with(**p)) {
        return (Some(prefix.trim_end_matches(':').to_owned()), &line[prefix.len()..]);
    }
    match line.strip_prefix('(').and_then(|l| l.strip_suffix(')')) {
        Some(inner) => (Some("()".to_owned()), inner),
        None => (None, line),
    }
}

/// Takes one token as a number or a `label:value` pair; false when it is neither.
fn take(fields: &mut Fields, token: &str) -> bool {
    if let Ok(value) = token.parse::<f64>() {
        fields.values.push(value);
        return fields.labels.is_empty() && value.is_finite();
    }
    let Some((label, value)) = token.split_once([':', '=']) else { return false };
    match value.trim().parse::<f64>() {
        Ok(value) if value.is_finite() && !label.is_empty() && fields.values.len() == fields.labels.len() => {
            fields.labels.push(label.trim().to_owned());
            fields.values.push(value);
            true
        }
        _ => false,
    }
}

fn words(tokens: &[&str]) -> Words {
    let is_name = |t: &&str| t.chars().next().is_some_and(|c| c.is_alphabetic() || c == '#' || c == '_');
    match tokens.len() >= 3 && tokens.iter().all(is_name) {
        true => Words::Header(tokens.iter().map(|t| t.trim_start_matches('#').to_owned()).collect()),
        false => Words::Text,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_sketchs_line_comes_apart_into_its_prefix_labels_and_values() {
        let i2c = fields("a/g:\t-76\t-2359\t16688\t12\t-3\t5\r").unwrap();
        assert_eq!((i2c.prefix.as_deref(), i2c.values.len(), i2c.commas), (Some("a/g"), 6, false));
        let raw = fields("Raw:812,-40,8190,3,-1,0,0,0,0").unwrap();
        assert_eq!((raw.prefix.as_deref(), raw.values[2], raw.commas), (Some("Raw"), 8190.0, true));
        let tuple = fields("(0.0634, -0.0493, 0.9298)").unwrap();
        assert_eq!((tuple.prefix.as_deref(), tuple.values), (Some("()"), vec![0.0634, -0.0493, 0.9298]));
        let plot = fields("AccelX:0.61,AccelY:-0.45,AccelZ:9.10, GyroX:-0.02,GyroY:0.01,GyroZ:0.00").unwrap();
        assert_eq!((plot.labels[3].as_str(), plot.values[2]), ("GyroX", 9.10));
        assert_eq!(fields("12 -3 16384").unwrap().values, vec![12.0, -3.0, 16384.0]);
    }

    #[test]
    fn headers_and_text_are_told_apart_and_neither_is_data() {
        assert_eq!(
            fields("millis,ax,ay,az").unwrap_err(),
            Words::Header(vec!["millis".into(), "ax".into(), "ay".into(), "az".into()])
        );
        assert_eq!(
            fields("MPU6050 connection successful").unwrap_err(),
            Words::Header(["MPU6050", "connection", "successful"].map(String::from).to_vec())
        );
        assert_eq!(fields(">>> ").unwrap_err(), Words::Text);
        assert_eq!(fields("ets Jun  8 2016 00:22:57").unwrap_err(), Words::Text);
        assert_eq!(fields("ax:1 2 3").unwrap_err(), Words::Text);
    }
}
