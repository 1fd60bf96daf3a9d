//! [`PositionMap`]: one optional value per face, the one container of per-face data.

use serde::{Deserialize, Serialize};

use super::Position;

/// One optional value per position, indexed by [`Position`]: the one container of per-face data
/// (the chip's kept captures, the readings of a six-position fit, the set of captured faces).
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub struct PositionMap<T>([Option<T>; 6]);

impl<T> Default for PositionMap<T> {
    fn default() -> Self {
        PositionMap([None, None, None, None, None, None])
    }
}

impl<T> PositionMap<T> {
    /// An empty map.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds the value of a position; `Err(position)` when it already has one (which is kept).
    pub fn insert(&mut self, position: Position, value: T) -> Result<(), Position> {
        let slot = &mut self.0[position.index()];
        if slot.is_some() {
            return Err(position);
        }
        *slot = Some(value);
        Ok(())
    }

    /// Adds or replaces the value of a position.
    pub fn replace(&mut self, position: Position, value: T) {
        self.0[position.index()] = Some(value);
    }

    /// Forgets every value.
    pub fn clear(&mut self) {
        *self = Self::default();
    }

    /// The value of a position, if any.
    pub fn get(&self, position: Position) -> Option<&T> {
        self.0[position.index()].as_ref()
    }

    /// The positions that have a value, in the order of [`Position::ALL`].
    pub fn present(&self) -> impl Iterator<Item = Position> + '_ {
        Position::ALL.into_iter().filter(|p| self.get(*p).is_some())
    }

    /// The first position without a value, in the order of [`Position::ALL`].
    pub fn first_missing(&self) -> Option<Position> {
        Position::ALL.into_iter().find(|p| self.get(*p).is_none())
    }

    /// Which positions have a value, without the values.
    pub fn marks(&self) -> PositionMap<()> {
        PositionMap(self.0.each_ref().map(|v| v.as_ref().map(|_| ())))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn marks_show_which_positions_have_a_value_and_insert_keeps_the_first() {
        let mut map = PositionMap::new();
        map.replace(Position::PosZ, 1.5);
        assert_eq!(map.insert(Position::PosZ, 2.5), Err(Position::PosZ));
        assert_eq!(map.get(Position::PosZ), Some(&1.5));
        assert_eq!(map.marks().present().collect::<Vec<_>>(), [Position::PosZ]);
        assert_eq!(map.first_missing(), Some(Position::PosX));
        map.clear();
        assert_eq!(map.present().count(), 0);
    }
}
