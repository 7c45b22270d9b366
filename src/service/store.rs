//! The server's embedded store: one redb file, `pairs.redb` in the
//! configured data directory, holding each registered profile pair as the
//! encoded canonical registration ([`pb::RegisterProfilePairRequest`] with
//! the canonical spec), keyed by the pair's id. Only the inputs are kept;
//! the prepared geometry is rebuilt from them after a restart, on first
//! use. Plain synchronous code: callers run it off the async runtime.

use std::path::Path;

use prost::Message;
use redb::{Database, ReadableDatabase, ReadableTable, TableDefinition};

use crate::service::pb;

/// id -> encoded canonical registration.
const PAIRS: TableDefinition<&str, &[u8]> = TableDefinition::new("profile_pairs_v1");

/// File name of the store in the data directory.
pub const FILE_NAME: &str = "pairs.redb";

/// A stored registration: its id and request.
pub type StoredPair = (String, pb::RegisterProfilePairRequest);

/// A stored entry that could not be decoded: its id and the reason.
pub type UndecodedPair = (String, String);

/// An open store.
pub struct PairStore {
    db: Database,
}

fn io(what: &str, e: impl std::fmt::Display) -> std::io::Error {
    std::io::Error::other(format!("profile pair store: {what}: {e}"))
}

impl PairStore {
    /// Opens (or creates) the store in `dir`, creating the directory.
    pub fn open(dir: &Path) -> std::io::Result<Self> {
        std::fs::create_dir_all(dir)
            .map_err(|e| io(&format!("cannot create {}", dir.display()), e))?;
        let path = dir.join(FILE_NAME);
        let db = Database::create(&path).map_err(|e| io(&path.display().to_string(), e))?;
        // Create the table so that readers find it.
        let tx = db.begin_write().map_err(|e| io("write", e))?;
        tx.open_table(PAIRS).map_err(|e| io("table", e))?;
        tx.commit().map_err(|e| io("commit", e))?;
        Ok(Self { db })
    }

    /// Stores (or replaces) the registration of `id`.
    pub fn put(
        &self,
        id: &str,
        registration: &pb::RegisterProfilePairRequest,
    ) -> std::io::Result<()> {
        let bytes = registration.encode_to_vec();
        let tx = self.db.begin_write().map_err(|e| io("write", e))?;
        {
            let mut t = tx.open_table(PAIRS).map_err(|e| io("table", e))?;
            t.insert(id, bytes.as_slice())
                .map_err(|e| io("insert", e))?;
        }
        tx.commit().map_err(|e| io("commit", e))
    }

    /// Removes the registration of `id`; whether there was one.
    pub fn remove(&self, id: &str) -> std::io::Result<bool> {
        let tx = self.db.begin_write().map_err(|e| io("write", e))?;
        let found = {
            let mut t = tx.open_table(PAIRS).map_err(|e| io("table", e))?;
            let found = t.remove(id).map_err(|e| io("remove", e))?.is_some();
            found
        };
        tx.commit().map_err(|e| io("commit", e))?;
        Ok(found)
    }

    /// Every stored registration, by id; entries that cannot be decoded are
    /// returned as errors (id, message) and left in place.
    pub fn load_all(&self) -> std::io::Result<(Vec<StoredPair>, Vec<UndecodedPair>)> {
        let tx = self.db.begin_read().map_err(|e| io("read", e))?;
        let t = tx.open_table(PAIRS).map_err(|e| io("table", e))?;
        let mut good = Vec::new();
        let mut bad = Vec::new();
        for row in t.iter().map_err(|e| io("iterate", e))? {
            let (k, v) = row.map_err(|e| io("read", e))?;
            let id = k.value().to_string();
            match pb::RegisterProfilePairRequest::decode(v.value()) {
                Ok(r) => good.push((id, r)),
                Err(e) => bad.push((id, e.to_string())),
            }
        }
        Ok((good, bad))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registrations_survive_reopening_and_removal_is_durable() {
        let dir = tempfile::tempdir().unwrap();
        let reg = pb::RegisterProfilePairRequest {
            label: "x".into(),
            pair: Some(pb::register_profile_pair_request::Pair::BuiltinPair(
                "mbench_s1002_uic60".into(),
            )),
        };
        {
            let s = PairStore::open(dir.path()).unwrap();
            s.put("a", &reg).unwrap();
            s.put("b", &reg).unwrap();
            assert!(s.remove("b").unwrap());
            assert!(!s.remove("b").unwrap());
        }
        let s = PairStore::open(dir.path()).unwrap();
        let (good, bad) = s.load_all().unwrap();
        assert!(bad.is_empty());
        assert_eq!(good.len(), 1);
        assert_eq!(good[0].0, "a");
        assert_eq!(good[0].1, reg);
    }
}
