//! What the runs of one campaign share of their static solves: a value made once by whichever
//! run needs it first, waited for (not made again) by the others, and kept for the runs after
//! them, by a blake3 hash of what it depends on. Pure: no I/O.

use std::sync::{Arc, Mutex, OnceLock};

/// One value, made once by whichever run needs it first.
type Slot<T> = Arc<OnceLock<Arc<T>>>;

/// Values by key, at most `KEEP` of them (the oldest is dropped first).
pub(super) struct Kept<T, const KEEP: usize> {
    slots: Mutex<Vec<([u8; 32], Slot<T>)>>,
}

impl<T, const KEEP: usize> Default for Kept<T, KEEP> {
    fn default() -> Self {
        Kept { slots: Mutex::new(Vec::new()) }
    }
}

impl<T, const KEEP: usize> Kept<T, KEEP> {
    /// How many values have been made and are still kept.
    pub(super) fn len(&self) -> usize {
        self.lock().iter().filter(|(_, slot)| slot.get().is_some()).count()
    }

    /// The value of `key`, made by `make` on a miss; while another caller makes it, waited for.
    pub(super) fn get(&self, key: [u8; 32], make: impl FnOnce() -> T) -> Arc<T> {
        let slot = {
            let mut slots = self.lock();
            match slots.iter().find(|(k, _)| *k == key) {
                Some((_, slot)) => slot.clone(),
                None => {
                    if slots.len() == KEEP {
                        slots.remove(0);
                    }
                    slots.push((key, Arc::default()));
                    slots.last().expect("just pushed").1.clone()
                }
            }
        };
        slot.get_or_init(|| Arc::new(make())).clone()
    }

    /// Drops the value of `key`: the next [`Kept::get`] makes it again.
    pub(super) fn forget(&self, key: [u8; 32]) {
        self.lock().retain(|(k, _)| *k != key);
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<([u8; 32], Slot<T>)>> {
        self.slots.lock().expect("the cache is never poisoned")
    }
}
