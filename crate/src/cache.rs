//! A small cache of built models, per thread: the page calls an export again and again with the
//! same machine (the defects, then an identification, then another identification), and a model
//! (the chain, the poses along a path, the sensitivities) costs far more than the call's own
//! work. Each cache keeps its last [`CAPACITY`] models, keyed by (a copy of) the inputs the model
//! depends on, the most recently used last. Keys compare with `==`: no text is written per call
//! (a key written as text, floats and all, cost more than the identification it saved under
//! WebAssembly). A key holding a NaN never matches, so its model is built each time; `-0.0`
//! and `0.0` match, and build the same model.
//!
//! Per thread (`thread_local!`): WebAssembly runs one thread, and native callers on several
//! threads each get their own, with no lock.

use crate::error::Result;
use std::cell::RefCell;
use std::rc::Rc;
use std::thread::LocalKey;

/// Models kept per cache.
pub const CAPACITY: usize = 16;

/// The models of one cache: (key, model), least recently used first.
pub type Models<K, T> = RefCell<Vec<(K, Rc<T>)>>;

/// The model of `key` from `cache`, or `build()` kept under `key` (the least recently used
/// model dropped when the cache is full). A failed build is not kept.
pub fn get_or_build<K: PartialEq + 'static, T: 'static>(
    cache: &'static LocalKey<Models<K, T>>,
    key: K,
    build: impl FnOnce() -> Result<T>,
) -> Result<Rc<T>> {
    let hit = cache.with(|c| {
        let mut c = c.borrow_mut();
        let i = c.iter().position(|(k, _)| *k == key)?;
        let entry = c.remove(i);
        let model = entry.1.clone();
        c.push(entry);
        Some(model)
    });
    if let Some(model) = hit {
        return Ok(model);
    }
    let model = Rc::new(build()?);
    cache.with(|c| {
        let mut c = c.borrow_mut();
        if c.len() >= CAPACITY {
            c.remove(0);
        }
        c.push((key, model.clone()));
    });
    Ok(model)
}

#[cfg(test)]
mod tests {
    use super::*;

    thread_local! {
        static TEST: Models<String, usize> = const { RefCell::new(Vec::new()) };
    }

    #[test]
    fn builds_once_per_key_and_keeps_the_last_ones() {
        let mut builds = 0;
        let mut get = |k: usize| {
            *get_or_build(&TEST, k.to_string(), || {
                builds += 1;
                Ok(k)
            })
            .unwrap_or_else(|_| Rc::new(usize::MAX))
        };
        assert_eq!(get(1), 1);
        assert_eq!(get(1), 1);
        for k in 2..=CAPACITY + 1 {
            assert_eq!(get(k), k);
        }
        // 1 was the least recently used: dropped, built again.
        assert_eq!(get(1), 1);
        assert_eq!(builds, CAPACITY + 2);
        assert!(TEST.with(|c| c.borrow().len()) <= CAPACITY);
        // A failed build is not kept.
        let failed = get_or_build(&TEST, "bad".into(), || Err(crate::Error::field("x", "no")));
        assert!(failed.is_err());
        assert!(TEST.with(|c| c.borrow().iter().all(|(k, _)| k != "bad")));
    }
}
