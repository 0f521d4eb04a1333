//! Names that become file names or table columns, checked when the study is read, so a run
//! never computes everything and then fails while writing its tables.

use crate::units::Dimension;
use crate::value::column_name;

/// Longest file-name component that ext4, XFS, Btrfs, APFS and NTFS accept, in bytes.
pub const MAX_FILE_NAME_BYTES: usize = 255;

/// Bytes kept free for what the engine adds around a name in a file name: `.summary_` and
/// `.parquet.tmp` (21 bytes) around a summary name, a staging prefix and suffix (about 40 bytes)
/// around the results folder, and a margin for later additions.
pub const NAME_AFFIX_BYTES: usize = 64;

/// Longest study or summary name, in bytes (both become file or folder names).
pub const MAX_NAME_BYTES: usize = MAX_FILE_NAME_BYTES - NAME_AFFIX_BYTES;

/// Checks a study name, which names the results folder `results/<study>/`: letters, digits,
/// '-', '_' and '.', not starting with '.' (hidden, or the folders `.` and `..`) or '-' (read as
/// an option by command-line tools), at most [`MAX_NAME_BYTES`] bytes.
pub(super) fn check_study_name(name: &str) -> Result<(), String> {
    let valid_chars = name
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'));
    if name.is_empty() || !valid_chars || name.starts_with(['.', '-']) {
        return Err(format!(
            "'{name}' is not a valid study name: use letters, digits, '-', '_' and '.', not \
             starting with '.' or '-' (it names the results folder)"
        ));
    }
    check_length(name, "study names")
}

/// Checks the length of a name that becomes part of a file name.
pub(super) fn check_length(name: &str, what: &str) -> Result<(), String> {
    if name.len() > MAX_NAME_BYTES {
        return Err(format!(
            "the name is {} bytes long; {what} are at most {MAX_NAME_BYTES} bytes (file names \
             are at most {MAX_FILE_NAME_BYTES} bytes, less {NAME_AFFIX_BYTES} for what asperity \
             adds to them); use a shorter name",
            name.len()
        ));
    }
    Ok(())
}

/// Every column name `name` can give: `<name>` or `<name>_<SI symbol>`, whatever its dimension.
fn column_forms(name: &str) -> Vec<String> {
    let mut forms: Vec<String> = Dimension::ALL
        .iter()
        .map(|&d| column_name(name, d))
        .collect();
    forms.dedup();
    forms
}

/// Columns of one table as a study declares them: each entry is what declares the column, where,
/// and the column names it can give. Two entries that can give the same column name would make
/// the table unwritable.
#[derive(Default)]
pub(super) struct Columns {
    entries: Vec<(String, Vec<String>)>,
}

impl Columns {
    /// A column the engine writes itself (`scenario`, `status`, `<node>_key`).
    pub(super) fn fixed(&mut self, column: &str, why: &str) {
        let described = format!("the column '{column}' ({why})");
        self.entries.push((described, vec![column.to_string()]));
    }

    /// A column named after `name` with a unit suffix of its dimension; on a clash with a
    /// column added before, the clause that names both.
    pub(super) fn add(&mut self, name: &str, described: String) -> Result<(), String> {
        let forms = column_forms(name);
        if let Some((other, _)) = self
            .entries
            .iter()
            .find(|(_, f)| f.iter().any(|c| forms.contains(c)))
        {
            return Err(format!("{described} would give the same column as {other}"));
        }
        self.entries.push((described, forms));
        Ok(())
    }
}
