//! The server's embedded store: one redb file, `pairs.redb` in the
//! configured data directory, holding each registered profile pair as the
//! encoded canonical registration ([`pb::RegisterProfilePairRequest`] with
//! the canonical spec), keyed by the pair's id, and a format marker. Only
//! the inputs are kept; the prepared geometry is rebuilt from them after a
//! restart, on first use. Plain synchronous code: callers run it off the
//! async runtime.
//!
//! Opening never turns something else into an empty store: a 0-byte file,
//! a file that is not a redb database, and a redb database without the
//! marker (or the pairs' table) are errors naming the file and what to do;
//! so is a file another process holds open. Whether each record still
//! matches its id is checked by the registry
//! ([`crate::service::pairs::PairRegistry::open`]), since the id is the hash
//! of the canonical content.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use prost::Message;
use redb::{
    Database, DatabaseError, ReadableDatabase, ReadableTable, ReadableTableMetadata, StorageError,
    TableDefinition, TableError,
};
use thiserror::Error;

use crate::service::pb;

/// id -> encoded canonical registration.
const PAIRS: TableDefinition<&str, &[u8]> = TableDefinition::new("profile_pairs_v1");

/// key -> value: the format marker.
const META: TableDefinition<&str, &str> = TableDefinition::new("railcontact_meta");

/// Key of the format marker in [`META`].
const FORMAT_KEY: &str = "format";

/// The format marker of this version's stores.
pub const FORMAT: &str = "railcontact.profile_pairs/1";

/// File name of the store in the data directory.
pub const FILE_NAME: &str = "pairs.redb";

/// What to do about a store that cannot be used, said once for every error.
const REMEDY: &str = "move the file away (or restore it from a backup), or give the server \
                      another data directory (--data-dir, RAILCONTACT_DATA_DIR, data_dir)";

/// Why the store cannot be opened or used. Every message names the file.
#[derive(Debug, Error)]
pub enum StoreError {
    /// The file is empty (0 bytes): not a store, and not made one, so that
    /// a truncated store does not silently become an empty one.
    #[error(
        "profile pair store {}: the file is empty (0 bytes), not a railcontact store; \
         its registrations are gone (truncated?). {REMEDY}; the server does not start \
         with an empty store in its place",
        path.display()
    )]
    Empty {
        /// The file.
        path: PathBuf,
    },
    /// The file is not a store of this server: not a redb database, or one
    /// without the format marker and the pairs' table.
    #[error(
        "profile pair store {}: not a railcontact profile pair store ({reason}); {REMEDY}",
        path.display()
    )]
    Foreign {
        /// The file.
        path: PathBuf,
        /// What was found.
        reason: String,
    },
    /// Another process holds the file open.
    #[error(
        "profile pair store {}: the file is locked by another process (redb: Database \
         already open. Cannot acquire lock); probably another railcontact server uses this \
         data directory: stop it, or give this server its own directory with --data-dir",
        path.display()
    )]
    Locked {
        /// The file.
        path: PathBuf,
    },
    /// The file could not be read or written.
    #[error("profile pair store {}: {what}: {message}", path.display())]
    Io {
        /// The file (or directory).
        path: PathBuf,
        /// What was being done.
        what: &'static str,
        /// The cause.
        message: String,
    },
}

/// A stored record: its id and either its registration or why it cannot
/// be decoded.
pub type StoredRecord = (String, Result<pb::RegisterProfilePairRequest, String>);

/// An open store.
pub struct PairStore {
    db: Database,
    path: PathBuf,
    /// Encoded bytes of the records, summed.
    bytes: AtomicU64,
}

impl PairStore {
    /// Opens the store in `dir`, creating the directory and, when there is
    /// no file yet, a new store. An existing file must be a store of this
    /// server (see [`StoreError`]).
    pub fn open(dir: &Path) -> Result<Self, StoreError> {
        let path = dir.join(FILE_NAME);
        let io = |what: &'static str, e: &dyn std::fmt::Display| StoreError::Io {
            path: path.clone(),
            what,
            message: e.to_string(),
        };
        std::fs::create_dir_all(dir).map_err(|e| io("cannot create its directory", &e))?;
        let existing = match std::fs::metadata(&path) {
            Ok(m) => Some(m.len()),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
            Err(e) => return Err(io("cannot read the file's metadata", &e)),
        };
        if existing == Some(0) {
            return Err(StoreError::Empty { path });
        }
        let opened = match existing {
            Some(_) => Database::open(&path),
            None => Database::create(&path),
        };
        let db = opened.map_err(|e| match e {
            DatabaseError::DatabaseAlreadyOpen => StoreError::Locked { path: path.clone() },
            // The file cannot be read (permissions, a directory in its
            // place): say so, not that it is some other file.
            DatabaseError::Storage(StorageError::Io(e))
                if e.kind() == std::io::ErrorKind::PermissionDenied =>
            {
                io(
                    "cannot open it",
                    &format!("{e} (the server's user must be able to read and write it)"),
                )
            }
            DatabaseError::Storage(StorageError::Io(e))
                if e.kind() == std::io::ErrorKind::IsADirectory =>
            {
                io("cannot open it", &e)
            }
            other if existing.is_some() => StoreError::Foreign {
                path: path.clone(),
                reason: format!("redb cannot open it: {other}"),
            },
            other => io("cannot create", &other),
        })?;
        let store = Self {
            db,
            path: path.clone(),
            bytes: AtomicU64::new(0),
        };
        match existing {
            Some(_) => store.check_marker()?,
            None => store.write_marker()?,
        }
        let bytes = store.sum_bytes()?;
        store.bytes.store(bytes, Ordering::Relaxed);
        Ok(store)
    }

    /// The store's file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Encoded bytes of the stored records, summed.
    pub fn bytes(&self) -> u64 {
        self.bytes.load(Ordering::Relaxed)
    }

    fn io(&self, what: &'static str, e: impl std::fmt::Display) -> StoreError {
        StoreError::Io {
            path: self.path.clone(),
            what,
            message: e.to_string(),
        }
    }

    fn foreign(&self, reason: impl Into<String>) -> StoreError {
        StoreError::Foreign {
            path: self.path.clone(),
            reason: reason.into(),
        }
    }

    /// Writes the marker and creates the pairs' table.
    fn write_marker(&self) -> Result<(), StoreError> {
        let tx = self.db.begin_write().map_err(|e| self.io("write", e))?;
        {
            let mut meta = tx.open_table(META).map_err(|e| self.io("table", e))?;
            meta.insert(FORMAT_KEY, FORMAT)
                .map_err(|e| self.io("insert", e))?;
            tx.open_table(PAIRS).map_err(|e| self.io("table", e))?;
        }
        tx.commit().map_err(|e| self.io("commit", e))
    }

    /// Checks the marker of an existing file. A store of the first version
    /// (the pairs' table, no marker) gets the marker.
    fn check_marker(&self) -> Result<(), StoreError> {
        let tx = self.db.begin_read().map_err(|e| self.io("read", e))?;
        let has_pairs = match tx.open_table(PAIRS) {
            Ok(_) => true,
            Err(TableError::TableDoesNotExist(_)) => false,
            Err(e) => return Err(self.foreign(format!("its table of pairs: {e}"))),
        };
        let marker = match tx.open_table(META) {
            Ok(t) => t
                .get(FORMAT_KEY)
                .map_err(|e| self.io("read", e))?
                .map(|v| v.value().to_string()),
            Err(TableError::TableDoesNotExist(_)) => None,
            Err(e) => return Err(self.foreign(format!("its metadata table: {e}"))),
        };
        drop(tx);
        match (marker, has_pairs) {
            (Some(m), true) if m == FORMAT => Ok(()),
            (Some(m), _) => Err(self.foreign(format!(
                "format marker {:?}, expected {FORMAT:?}",
                crate::wheelrail::profile::quote(&m)
            ))),
            (None, true) => self.write_marker(),
            (None, false) => Err(self
                .foreign("a redb database without railcontact's format marker and table of pairs")),
        }
    }

    fn sum_bytes(&self) -> Result<u64, StoreError> {
        let tx = self.db.begin_read().map_err(|e| self.io("read", e))?;
        let t = tx.open_table(PAIRS).map_err(|e| self.io("table", e))?;
        let mut sum = 0;
        for row in t.iter().map_err(|e| self.io("iterate", e))? {
            let (_, v) = row.map_err(|e| self.io("read a record", e))?;
            sum += v.value().len() as u64;
        }
        Ok(sum)
    }

    /// Stores (or replaces) the registration of `id`.
    pub fn put(
        &self,
        id: &str,
        registration: &pb::RegisterProfilePairRequest,
    ) -> Result<(), StoreError> {
        let bytes = registration.encode_to_vec();
        let tx = self.db.begin_write().map_err(|e| self.io("write", e))?;
        let old = {
            let mut t = tx.open_table(PAIRS).map_err(|e| self.io("table", e))?;
            let old = t
                .insert(id, bytes.as_slice())
                .map_err(|e| self.io("insert", e))?;
            old.map_or(0, |v| v.value().len() as u64)
        };
        tx.commit().map_err(|e| self.io("commit", e))?;
        self.bytes.fetch_add(bytes.len() as u64, Ordering::Relaxed);
        self.bytes.fetch_sub(old, Ordering::Relaxed);
        Ok(())
    }

    /// Removes the registration of `id`; whether there was one.
    pub fn remove(&self, id: &str) -> Result<bool, StoreError> {
        let tx = self.db.begin_write().map_err(|e| self.io("write", e))?;
        let old = {
            let mut t = tx.open_table(PAIRS).map_err(|e| self.io("table", e))?;
            let old = t.remove(id).map_err(|e| self.io("remove", e))?;
            old.map(|v| v.value().len() as u64)
        };
        tx.commit().map_err(|e| self.io("commit", e))?;
        if let Some(n) = old {
            self.bytes.fetch_sub(n, Ordering::Relaxed);
        }
        Ok(old.is_some())
    }

    /// Every stored record, by id; a record that cannot be decoded comes
    /// with the reason (and is left in place).
    pub fn load_all(&self) -> Result<Vec<StoredRecord>, StoreError> {
        let tx = self.db.begin_read().map_err(|e| self.io("read", e))?;
        let t = tx.open_table(PAIRS).map_err(|e| self.io("table", e))?;
        let mut out = Vec::with_capacity(t.len().unwrap_or(0) as usize);
        for row in t.iter().map_err(|e| self.io("iterate", e))? {
            let (k, v) = row.map_err(|e| self.io("read a record", e))?;
            let record = pb::RegisterProfilePairRequest::decode(v.value())
                .map_err(|e| format!("cannot be decoded: {e}"));
            out.push((k.value().to_string(), record));
        }
        Ok(out)
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
        let n = reg.encoded_len() as u64;
        {
            let s = PairStore::open(dir.path()).unwrap();
            s.put("a", &reg).unwrap();
            s.put("b", &reg).unwrap();
            s.put("b", &reg).unwrap();
            assert_eq!(s.bytes(), 2 * n);
            assert!(s.remove("b").unwrap());
            assert!(!s.remove("b").unwrap());
            assert_eq!(s.bytes(), n);
        }
        let s = PairStore::open(dir.path()).unwrap();
        assert_eq!(s.bytes(), n);
        let all = s.load_all().unwrap();
        assert_eq!(all.len(), 1);
        assert_eq!(all[0].0, "a");
        assert_eq!(all[0].1.as_ref().unwrap(), &reg);
    }

    #[test]
    fn empty_foreign_and_locked_files_are_refused_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(FILE_NAME);
        let shown = path.display().to_string();
        std::fs::write(&path, b"").unwrap();
        let e = PairStore::open(dir.path())
            .err()
            .expect("empty file refused");
        assert!(matches!(e, StoreError::Empty { .. }), "{e}");
        assert!(e.to_string().contains(&shown), "{e}");
        assert_eq!(std::fs::metadata(&path).unwrap().len(), 0, "left as it was");
        std::fs::write(&path, "not a database\n".repeat(500)).unwrap();
        let e = PairStore::open(dir.path())
            .err()
            .expect("text file refused");
        assert!(matches!(e, StoreError::Foreign { .. }), "{e}");
        // A redb database of someone else.
        std::fs::remove_file(&path).unwrap();
        {
            let db = Database::create(&path).unwrap();
            let tx = db.begin_write().unwrap();
            let other: TableDefinition<&str, u64> = TableDefinition::new("other");
            tx.open_table(other).unwrap().insert("k", 1).unwrap();
            tx.commit().unwrap();
        }
        let e = PairStore::open(dir.path())
            .err()
            .expect("foreign redb refused");
        assert!(
            matches!(e, StoreError::Foreign { .. }) && e.to_string().contains("marker"),
            "{e}"
        );
        // A store in use.
        std::fs::remove_file(&path).unwrap();
        let _first = PairStore::open(dir.path()).unwrap();
        let e = PairStore::open(dir.path())
            .err()
            .expect("second open refused");
        assert!(matches!(e, StoreError::Locked { .. }), "{e}");
        let m = e.to_string();
        assert!(
            m.contains(&shown)
                && m.contains("another railcontact server")
                && m.contains("--data-dir"),
            "{m}"
        );
    }

    /// A file that cannot be opened is reported as such, not as a file of
    /// another kind (a directory in its place; permissions, which a test
    /// run as root cannot take away, give the same error with a hint).
    #[test]
    fn a_file_that_cannot_be_opened_is_not_called_foreign() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(FILE_NAME);
        std::fs::create_dir(&path).unwrap();
        let e = PairStore::open(dir.path())
            .err()
            .expect("a directory refused");
        let m = e.to_string();
        assert!(matches!(e, StoreError::Io { .. }), "{m}");
        assert!(
            m.contains("cannot open it") && m.contains(&path.display().to_string()),
            "{m}"
        );
        assert!(!m.contains("not a railcontact"), "{m}");
    }
}
