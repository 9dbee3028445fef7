//! An open-addressing hash table keyed by grid coordinates.

use alloc::vec::Vec;

/// Open-addressing hash table from grid coordinates to small values. Lookups only:
/// nothing depends on its iteration order, so results stay deterministic.
pub(super) struct Table<V> {
    keys: Vec<u64>,
    values: Vec<V>,
    len: usize,
}

const EMPTY: u64 = 0;

impl<V: Copy + Default> Table<V> {
    /// An empty table with room for `slots` (a power of two) before it first grows.
    pub(super) fn with_slots(slots: usize) -> Self {
        Self {
            keys: alloc::vec![EMPTY; slots],
            values: alloc::vec![V::default(); slots],
            len: 0,
        }
    }

    fn key((x, y): (i32, i32)) -> u64 {
        // Doubled coordinates stay within ±2^30, so the offset keeps both halves positive and
        // the key nonzero.
        let x = (x as i64 + (1 << 31)) as u64;
        let y = (y as i64 + (1 << 31)) as u64;
        (x << 32) | y
    }

    fn slot(&self, key: u64) -> usize {
        let mask = self.keys.len() - 1;
        let bits = self.keys.len().trailing_zeros();
        (key.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - bits)) as usize & mask
    }

    /// The slot holding `key`, and `true`; else the empty slot where it would go, and
    /// `false`. The table is never full (it grows first), so the probe ends.
    fn probe(&self, key: u64) -> (usize, bool) {
        let mask = self.keys.len() - 1;
        let mut s = self.slot(key);
        loop {
            match self.keys[s] {
                k if k == key => return (s, true),
                EMPTY => return (s, false),
                _ => s = (s + 1) & mask,
            }
        }
    }

    pub(super) fn get(&self, at: (i32, i32)) -> Option<V> {
        match self.probe(Self::key(at)) {
            (s, true) => Some(self.values[s]),
            (_, false) => None,
        }
    }

    /// The value at `at`, and `false`; else `value`, inserted, and `true`. One probe.
    pub(super) fn get_or_insert(&mut self, at: (i32, i32), value: V) -> (V, bool) {
        self.room_for_one();
        let key = Self::key(at);
        match self.probe(key) {
            (s, true) => (self.values[s], false),
            (s, false) => {
                self.store(s, key, value);
                (value, true)
            }
        }
    }

    pub(super) fn insert(&mut self, at: (i32, i32), value: V) {
        self.room_for_one();
        let key = Self::key(at);
        let (s, _) = self.probe(key);
        self.store(s, key, value);
    }

    /// Writes `key` and `value` into slot `s`, counting the key if the slot was empty.
    fn store(&mut self, s: usize, key: u64, value: V) {
        if self.keys[s] == EMPTY {
            self.len += 1;
        }
        self.keys[s] = key;
        self.values[s] = value;
    }

    /// Grows the table if one more key would fill more than half its slots.
    fn room_for_one(&mut self) {
        if (self.len + 1) * 2 > self.keys.len() {
            self.grow();
        }
    }

    fn grow(&mut self) {
        let size = self.keys.len() * 2;
        let keys = core::mem::replace(&mut self.keys, alloc::vec![EMPTY; size]);
        let values = core::mem::replace(&mut self.values, alloc::vec![V::default(); size]);
        self.len = 0;
        for (key, value) in keys.into_iter().zip(values) {
            if key == EMPTY {
                continue;
            }
            let (s, _) = self.probe(key);
            self.store(s, key, value);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_grows_and_finds() {
        let mut t: Table<u32> = Table::with_slots(16);
        for i in -2000..2000 {
            t.insert((i, -i), i as u32);
        }
        for i in -2000..2000 {
            assert_eq!(t.get((i, -i)), Some(i as u32));
        }
        assert_eq!(t.get((1, 1)), None);
        t.insert((5, -5), 7);
        assert_eq!(t.get((5, -5)), Some(7));
    }

    #[test]
    fn table_get_or_insert_inserts_once() {
        let mut t: Table<u32> = Table::with_slots(16);
        for i in 0..1000 {
            assert_eq!(t.get_or_insert((i, 2 * i), i as u32), (i as u32, true));
        }
        for i in 0..1000 {
            assert_eq!(t.get_or_insert((i, 2 * i), 5000), (i as u32, false));
            assert_eq!(t.get((i, 2 * i)), Some(i as u32));
        }
        assert_eq!(t.len, 1000);
        assert_eq!(t.get((1, 1)), None);
    }
}
