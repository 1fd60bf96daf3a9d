//! Values a person types that name one of the core's enums (`--to c-fixed`, `--input-unit m/s2`,
//! `--sketch micropython`): the core names them (strum, with each doc line as help) without knowing
//! clap, and this turns those names into clap's possible values, so `--help` lists each with its
//! help and a wrong value is refused naming the right ones.

use std::str::FromStr;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use strum::{EnumMessage, IntoEnumIterator};

/// The value parser of an enum the core names.
pub fn named<T>() -> impl TypedValueParser<Value = T>
where
    T: IntoEnumIterator + EnumMessage + Into<&'static str> + FromStr + Clone + Send + Sync + 'static,
    <T as FromStr>::Err: std::error::Error + Send + Sync + 'static,
{
    let values = T::iter().map(|value| {
        // NOTE: as clap's derive shows a one-line doc comment: without its closing full stop.
        let help = value.get_documentation().unwrap_or_default().trim_end_matches('.');
        PossibleValue::new(value.into()).help(help)
    });
    PossibleValuesParser::new(values).try_map(|name| name.parse::<T>())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::Target;
    use crate::stream::{AccelUnit, GyroUnit};

    fn names<T>() -> Vec<String>
    where
        T: IntoEnumIterator + EnumMessage + Into<&'static str> + FromStr + Clone + Send + Sync + 'static,
        <T as FromStr>::Err: std::error::Error + Send + Sync + 'static,
    {
        let parser = named::<T>();
        parser.possible_values().into_iter().flatten().map(|v| v.get_name().to_owned()).collect()
    }

    #[test]
    fn the_names_a_person_types_are_the_ones_the_command_line_always_took() {
        assert_eq!(
            names::<AccelUnit>(),
            ["g", "mg", "m/s2", "counts-2g", "counts-4g", "counts-8g", "counts-16g", "motioncal-counts"]
        );
        let gyro = [
            "deg/s",
            "rad/s",
            "counts-250dps",
            "counts-500dps",
            "counts-1000dps",
            "counts-2000dps",
            "motioncal-counts",
        ];
        assert_eq!(names::<GyroUnit>(), gyro);
        assert_eq!(names::<Target>()[..3], ["c", "c-fixed", "rust"]);
        assert_eq!(names::<Target>()[4..6], ["adafruit-json", "adafruit-eeprom"]);
        assert_eq!(names::<Target>()[11], "i2cdevlib");
    }

    #[test]
    fn a_name_reads_as_its_value_and_an_unknown_one_is_refused() {
        let command = clap::Command::new("t").arg(clap::Arg::new("to").long("to").value_parser(named::<Target>()));
        let matches = command.clone().try_get_matches_from(["t", "--to", "c-fixed"]).unwrap();
        assert_eq!(matches.get_one::<Target>("to"), Some(&Target::CFixed));
        let refused = command.try_get_matches_from(["t", "--to", "cfixed"]).unwrap_err().to_string();
        assert!(refused.contains("possible values: c, c-fixed"), "{refused}");
    }
}
