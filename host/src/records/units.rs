//! accelcal's units as the test executives name them: UN/CEFACT Recommendation 20's name and code
//! (OpenHTF's `units` module lists them: K40, C62, CEL, DD, P1) and a suffix; the ones Rec. 20 has no
//! code for (mg, g/degC) keep a name and suffix with no code.

/// A unit as a record states it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Unit {
    pub name: &'static str,
    pub code: Option<&'static str>,
    pub suffix: &'static str,
}

/// accelcal's unit texts and their units. NOTE: accelcal's g is the gravity where the board was
/// captured (|a| = 1 at rest), which K40 (9.80665 m/s^2) stands for as closely as a code can.
const UNITS: [(&str, Unit); 7] = [
    ("g", Unit { name: "standard acceleration of free fall", code: Some("K40"), suffix: "gn" }),
    ("1", Unit { name: "one", code: Some("C62"), suffix: "1" }),
    ("degC", Unit { name: "degree Celsius", code: Some("CEL"), suffix: "°C" }),
    ("deg", Unit { name: "degree [unit of angle]", code: Some("DD"), suffix: "°" }),
    ("%", Unit { name: "percent", code: Some("P1"), suffix: "%" }),
    ("mg", Unit { name: "milli standard acceleration of free fall", code: None, suffix: "mg" }),
    ("g/degC", Unit { name: "standard acceleration of free fall per degree Celsius", code: None, suffix: "gn/°C" }),
];

/// The unit of accelcal's unit text: (name, code, suffix); an unknown text (a later certificate's)
/// named and suffixed by itself, with no code.
pub fn of(text: &str) -> (String, Option<&'static str>, String) {
    match UNITS.iter().find(|(t, _)| *t == text) {
        Some((_, u)) => (u.name.to_owned(), u.code, u.suffix.to_owned()),
        None => (text.to_owned(), None, text.to_owned()),
    }
}
