//! One printed line taken apart: what a terminal or a logger adds is passed over first (ANSI colours,
//! log prefixes such as ESPHome's `[D][sensor:094]:` and ESP-IDF's `I (1234) tag:`, ESPHome's
//! `Sending state ... with 2 decimals of accuracy`, decimal commas in a semicolon-separated line);
//! then the record prefix a sketch puts first (`a/g:`, `Raw:`, a tuple's parenthesis) and either
//! numbers or `label:value` pairs, separated by commas, tabs, spaces or semicolons; failing that, the
//! values found wherever they stand, each with the words before it as its label (`AcX = 1234 | ...`,
//! `Acceleration X: 0.12, Y: ...`, JSON objects, Python dictionaries, bracketed arrays) and the unit
//! words after it. Nothing here knows which dialect a line belongs to; [`super::dialect`] decides.

use super::units::{unit_word, UnitWord};

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
    /// How the line was written.
    pub form: Form,
    /// The unit each value's line names after it (`m/s^2`, `rad/s`, ...), when it names one.
    pub units: Vec<Option<UnitWord>>,
}

/// How a line was written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Form {
    /// Bare numbers or the Serial Plotter's `label:value` tokens.
    Plain,
    /// Numbers separated by semicolons with decimal commas (a European-locale CSV).
    DecimalCommas,
    /// A JSON object or a Python dictionary: `{...}`.
    Braced,
    /// A bracketed array: `[...]`.
    Bracketed,
    /// Values among words: `AcX = 1234 | AcY = ...`, `Acceleration X: 0.12, Y: ...`.
    Labelled,
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
/// The most words a label has (ESPHome's `'MPU6050 Accel X'`): more are a sentence, not a label.
const LABEL_WORDS: usize = 3;
/// Words after a temperature that name its unit (`25.43 degC`, `Temperature is 25.3 degrees C`).
const TEMPERATURE_WORDS: [&str; 6] = ["c", "°c", "degc", "degrees", "celsius", "*c"];

/// The fields of `line`, or what it holds instead.
pub(super) fn fields(line: &str) -> Result<Fields, Words> {
    let cleaned = passed_over(line);
    let (text, decimal_commas) = with_decimal_points(&cleaned);
    let text = text.trim_matches(|c: char| c.is_whitespace() || c == '\0');
    match plain(text) {
        Ok(mut parsed) => {
            if decimal_commas {
                (parsed.form, parsed.commas) = (Form::DecimalCommas, false);
            }
            Ok(parsed)
        }
        Err(words) => scattered(text).ok_or(words),
    }
}

/// The line without what a terminal or a logger adds around a sketch's words.
fn passed_over(line: &str) -> String {
    let line = without_ansi(line);
    let mut rest = line.trim_start_matches(|c: char| c.is_whitespace() || c == '\0');
    // NOTE: ESPHome's logger starts each line with `[level][tag:line]:` (esphome/core/log.h).
    while let Some(end) = log_tag_end(rest) {
        rest = rest[end + 1..].trim_start_matches(':').trim_start();
    }
    let rest = without_idf_prefix(rest);
    // NOTE: ESPHome's sensor.cpp logs "'%s': Sending state %.5f %s with %d decimals of accuracy".
    let rest = rest.split(" with ").next().filter(|_| rest.ends_with("decimals of accuracy")).unwrap_or(rest);
    rest.replacen("Sending state", "", 1)
}

/// Where a leading `[...]` that is a log's tag (`[D]`, `[sensor:094]`, `[12:34:56]`) ends: an array's
/// brackets hold commas or spaces, a tag neither.
fn log_tag_end(line: &str) -> Option<usize> {
    let end = line.strip_prefix('[')?.find(']')? + 1;
    let inside = &line[1..end];
    (!inside.is_empty() && !inside.contains([',', ' '])).then_some(end)
}

/// The line with its ANSI escape sequences (`ESC [ ... letter`: colours) taken out.
fn without_ansi(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '\u{1b}' {
            out.push(c);
            continue;
        }
        if chars.next_if_eq(&'[').is_some() {
            while chars.next().is_some_and(|c| !c.is_ascii_alphabetic()) {}
        }
    }
    out
}

/// The line without ESP-IDF's log prefix: a level letter, the milliseconds in brackets, the tag
/// and a colon (`I (1234) mpu6050: `, esp_log.h's LOG_FORMAT).
fn without_idf_prefix(line: &str) -> &str {
    let mut chars = line.chars();
    let level = chars.next().is_some_and(|c| "EWIDV".contains(c));
    let Some(after) = line.get(1..).and_then(|l| l.strip_prefix(" (")) else { return line };
    let Some((millis, tail)) = after.split_once(") ") else { return line };
    match (level, millis.chars().all(|c| c.is_ascii_digit()), tail.split_once(": ")) {
        (true, true, Some((_, message))) => message,
        _ => line,
    }
}

/// A semicolon-separated line whose commas stand between digits has decimal commas: they become points.
fn with_decimal_points(line: &str) -> (String, bool) {
    let bytes = line.as_bytes();
    let comma_in_number = (1..bytes.len().saturating_sub(1))
        .any(|i| bytes[i] == b',' && bytes[i - 1].is_ascii_digit() && bytes[i + 1].is_ascii_digit());
    match line.contains(';') && comma_in_number {
        true => (line.replace(',', "."), true),
        false => (line.to_owned(), false),
    }
}

/// Bare numbers or `label:value` tokens, each token one of them (the Serial Plotter's form, a CSV).
fn plain(line: &str) -> Result<Fields, Words> {
    let (prefix, body) = split_prefix(line);
    let commas = body.contains(',');
    let tokens: Vec<&str> = body.split([',', '\t', ' ', ';']).filter(|t| !t.is_empty()).collect();
    let mut parsed =
        Fields { prefix, labels: Vec::new(), values: Vec::new(), commas, form: Form::Plain, units: Vec::new() };
    for token in &tokens {
        if !take(&mut parsed, token) {
            return Err(words(&tokens));
        }
    }
    parsed.units = vec![None; parsed.values.len()];
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

/// What separates values and labels in a line of values among words.
const SEPARATORS: [char; 14] = [',', ';', '\t', ' ', '|', '{', '}', '[', ']', '(', ')', '"', '\'', '='];

/// Values found wherever they stand, each labelled by the words before it and with the unit word
/// after it; none when words follow the last value or only some values have labels (a boot line's
/// `ets Jun  8 2016 00:22:57`) or a label is a sentence rather than a name.
fn scattered(line: &str) -> Option<Fields> {
    let form = match line.chars().next() {
        Some('{') => Form::Braced,
        Some('[') => Form::Bracketed,
        _ => Form::Labelled,
    };
    let mut scan = Scan::default();
    for token in line.split(SEPARATORS).flat_map(|t| t.split_terminator(':')).filter(|t| !t.is_empty()) {
        scan.take(token);
    }
    scan.finish(form, line.contains(','))
}

/// A line's tokens taken one by one.
#[derive(Default)]
struct Scan {
    labels: Vec<String>,
    values: Vec<f64>,
    units: Vec<Option<UnitWord>>,
    /// Words since the last value: the next value's label.
    words: Vec<String>,
}

impl Scan {
    fn take(&mut self, token: &str) {
        if let Some(unit) = unit_word(token) {
            let waiting = self.units.iter().rposition(Option::is_some).map_or(0, |i| i + 1);
            self.units[waiting..].iter_mut().for_each(|u| *u = Some(unit));
        } else if let Some((value, unit)) = number(token) {
            self.labels.push(self.words.join(" "));
            self.words.clear();
            self.values.push(value);
            self.units.push(None);
            if let Some(unit) = unit {
                self.take(unit);
            }
        } else if !TEMPERATURE_WORDS.contains(&token.to_lowercase().as_str()) {
            self.words.push(token.to_owned());
        }
    }

    fn finish(mut self, form: Form, commas: bool) -> Option<Fields> {
        label_triples(&mut self.labels);
        let labelled = self.labels.iter().filter(|l| !l.is_empty()).count();
        let names = |l: &String| l.split(' ').count() <= LABEL_WORDS && l.split(' ').all(is_name);
        match (self.values.is_empty() || !self.words.is_empty(), labelled) {
            (true, _) => return None,
            (false, 0) => self.labels.clear(),
            (false, n) if n == self.labels.len() && self.labels.iter().all(names) => with_axis_heads(&mut self.labels),
            _ => return None,
        }
        let (labels, values, units) = (self.labels, self.values, self.units);
        Some(Fields { prefix: None, labels, values, commas, form, units })
    }
}

/// A number, or a number with its unit written on (`25.10°C`, `9.81m/s^2`): the unit's word.
fn number(token: &str) -> Option<(f64, Option<&str>)> {
    if let Ok(value) = token.parse::<f64>() {
        return value.is_finite().then_some((value, None));
    }
    let split = token.char_indices().map(|(i, _)| i).rev().find(|&i| i > 0 && token[..i].parse::<f64>().is_ok())?;
    let (value, unit) = (token[..split].parse::<f64>().ok()?, &token[split..]);
    let known = unit_word(unit).is_some() || TEMPERATURE_WORDS.contains(&unit.to_lowercase().as_str());
    (known && value.is_finite()).then_some((value, Some(unit)))
}

/// Whether a word can be part of a label: it starts with a letter or an underscore.
fn is_name(word: &str) -> bool {
    word.chars().next().is_some_and(|c| c.is_alphabetic() || c == '_')
}

/// A label before three values, the next two unlabelled, labels each by its axis:
/// `Accel: 0.01 -0.02 0.99 Gyro: ...` gives `Accel x`, `Accel y`, `Accel z`.
fn label_triples(labels: &mut [String]) {
    let n = labels.len();
    for i in 0..n.saturating_sub(2) {
        let triple = !labels[i].is_empty() && labels[i + 1].is_empty() && labels[i + 2].is_empty();
        if triple && (i + 3 == n || !labels[i + 3].is_empty()) {
            let head = labels[i].clone();
            for (k, axis) in ["x", "y", "z"].into_iter().enumerate() {
                labels[i + k] = format!("{head} {axis}");
            }
        }
    }
}

/// Labels that are an axis letter alone take the quantity of the label before them:
/// `Acceleration X: 0.12, Y: -0.34` labels its second value `Acceleration Y`.
fn with_axis_heads(labels: &mut [String]) {
    let is_axis = |w: &str| matches!(w, "x" | "y" | "z" | "X" | "Y" | "Z");
    for i in 1..labels.len() {
        let before: Vec<&str> = labels[i - 1].split(' ').collect();
        if is_axis(&labels[i]) && before.len() >= 2 && is_axis(before[before.len() - 1]) {
            labels[i] = format!("{} {}", before[..before.len() - 1].join(" "), labels[i]);
        }
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
    fn values_are_found_among_words_colours_log_prefixes_and_decimal_commas() {
        let playground = fields("AcX = 1234 | AcY = -56 | AcZ = 16012 | Tmp = 26.53 | GyX = -12").unwrap();
        assert_eq!(
            (playground.labels[3].as_str(), playground.values[2], playground.form),
            ("Tmp", 16012.0, Form::Labelled)
        );
        let adafruit = fields("Acceleration X: 0.12, Y: -0.34, Z: 9.81 m/s^2").unwrap();
        assert_eq!(adafruit.labels, ["Acceleration X", "Acceleration Y", "Acceleration Z"]);
        assert_eq!(adafruit.units[0], Some(UnitWord::Accel(super::super::AccelUnit::MetersPerSecond2)));
        let esphome = "\u{1b}[0;36m[D][sensor:093]: 'MPU6050 Gyro Y': Sending state -0.45802 °/s with 2 decimals of accuracy\u{1b}[0m";
        let esphome = fields(esphome).unwrap();
        assert_eq!((esphome.labels[0].as_str(), esphome.values.clone()), ("MPU6050 Gyro Y", vec![-0.45802]));
        assert_eq!(esphome.units[0], Some(UnitWord::Gyro(super::super::GyroUnit::DegPerS)));
        let idf = fields("\u{1b}[0;32mI (1327) mpu6050 test: acce_x:0.01, acce_y:-0.02, acce_z:0.99").unwrap();
        assert_eq!((idf.labels[2].as_str(), idf.values[2]), ("acce_z", 0.99));
        let json = fields("{\"t\":1712,\"ax\":0.11970,\"temp\":26.53}").unwrap();
        assert_eq!(
            (json.labels.clone(), json.values[1], json.form),
            (vec!["t".into(), "ax".into(), "temp".into()], 0.1197, Form::Braced)
        );
        let dict = fields("{'GyZ': -46, 'Tmp': 26.5294, 'AcX': 516}").unwrap();
        assert_eq!((dict.labels[0].as_str(), dict.values[0]), ("GyZ", -46.0));
        let array = fields("[0.11970, -0.3352, 9.80665, 0.0013]").unwrap();
        assert_eq!((array.labels.len(), array.values.len(), array.form), (0, 4, Form::Bracketed));
        let grouped = fields("Accel: 0.01 -0.02 0.99 Gyro: 0.1 0.2 0.3").unwrap();
        assert_eq!((grouped.labels[1].as_str(), grouped.labels[5].as_str()), ("Accel y", "Gyro z"));
        let european = fields("1,2340;0,0123;-0,0456;0,9981").unwrap();
        assert_eq!((european.values, european.form), (vec![1.234, 0.0123, -0.0456, 0.9981], Form::DecimalCommas));
        let kris = fields("Temperature is 26.53 degrees C").unwrap();
        assert_eq!((kris.labels[0].as_str(), kris.values[0]), ("Temperature is", 26.53));
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
        assert_eq!(fields("ax:1 2 3 4").unwrap_err(), Words::Text);
        for boot in ["configsip: 0, SPIWP:0xee", "mode:DIO, clock div:1", "load:0x3fff0030,len:1184", "Found 2 devices"]
        {
            assert!(fields(boot).is_err(), "{boot}");
        }
    }
}
