//! A time of day as the measurement files write it: `hh:mm` or `hh:mm:ss`.

use std::fmt;

/// Seconds since midnight on some clock (local or UTC), 0 ≤ seconds < 86 400. Equality and
/// order are f64's total order, so that they agree with each other.
#[derive(Debug, Clone, Copy)]
pub struct Clock {
    pub seconds: f64,
}

impl PartialEq for Clock {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other).is_eq()
    }
}

impl Eq for Clock {}

impl PartialOrd for Clock {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Clock {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.seconds.total_cmp(&other.seconds)
    }
}

impl Clock {
    /// Parses `hh:mm` or `hh:mm:ss` (seconds may have a fraction).
    pub fn parse(s: &str) -> Result<Clock, String> {
        let bad = || format!("`{s}` is not a time of day hh:mm[:ss]");
        let parts: Vec<&str> = s.trim().split(':').collect();
        if !(2..=3).contains(&parts.len()) {
            return Err(bad());
        }
        let h: u32 = parts[0].parse().map_err(|_| bad())?;
        let m: u32 = parts[1].parse().map_err(|_| bad())?;
        let sec: f64 = match parts.get(2) {
            Some(p) => p.parse().map_err(|_| bad())?,
            None => 0.0,
        };
        if h > 23 || m > 59 || !(0.0..60.0).contains(&sec) {
            return Err(bad());
        }
        Ok(Clock {
            seconds: f64::from(h * 3600 + m * 60) + sec,
        })
    }

    /// Decimal hours.
    pub fn hours(self) -> f64 {
        self.seconds / 3600.0
    }
}

impl fmt::Display for Clock {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = self.seconds.round() as u32;
        if s % 60 == 0 {
            write!(f, "{:02}:{:02}", s / 3600, s / 60 % 60)
        } else {
            write!(f, "{:02}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
        }
    }
}
