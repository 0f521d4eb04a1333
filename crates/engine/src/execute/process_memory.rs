//! The process's own memory as the kernel counts it: the resident set now (`VmRSS`) and its
//! peak since the process started (`VmHWM`), from `/proc/self/status` (Linux; `None` elsewhere
//! or when it cannot be read).

/// The resident set of this process now, bytes.
pub fn resident_bytes() -> Option<u64> {
    status_field("VmRSS:")
}

/// The peak resident set of this process since it started (its high-water mark), bytes.
pub fn peak_resident_bytes() -> Option<u64> {
    status_field("VmHWM:")
}

/// A `kB` field of `/proc/self/status`, bytes.
fn status_field(name: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    parse_kib_field(&status, name)
}

/// The value of the line `name  <n> kB` of a `/proc/<pid>/status` text, bytes.
fn parse_kib_field(status: &str, name: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with(name))?;
    let mut words = line[name.len()..].split_whitespace();
    let kib = words.next()?.parse::<u64>().ok()?;
    (words.next() == Some("kB")).then_some(kib * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_a_kib_field_of_a_status_text() {
        let status = "Name:\tasperity\nVmHWM:\t  215040 kB\nVmRSS:\t   10240 kB\n";
        assert_eq!(parse_kib_field(status, "VmHWM:"), Some(215_040 * 1024));
        assert_eq!(parse_kib_field(status, "VmRSS:"), Some(10_240 * 1024));
        assert_eq!(parse_kib_field(status, "VmSwap:"), None);
        assert_eq!(parse_kib_field("VmRSS:\t12 MB\n", "VmRSS:"), None);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn the_peak_is_at_least_the_resident_set() {
        let now = resident_bytes().expect("Linux has /proc/self/status");
        let peak = peak_resident_bytes().expect("Linux has /proc/self/status");
        assert!(now > 0 && peak >= now, "VmRSS {now}, VmHWM {peak}");
    }
}
