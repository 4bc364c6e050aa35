//! An Embree device with a build thread count and a memory-monitor callback that tallies what
//! Embree holds and holds it to the memory budget.

use crate::index::build_budget::room_for;
use embree3::{Config, Device};
use std::sync::Arc;
use std::sync::atomic::{AtomicIsize, AtomicUsize, Ordering};

/// A device, the running sum of the bytes its memory monitor reported and that sum's maximum.
pub(super) struct MonitoredDevice {
    pub device: Device,
    held: Arc<AtomicIsize>,
    peak: Arc<AtomicIsize>,
    /// The device's bytes at the allocation the budget refused; 0 while none was.
    refused_at: Arc<AtomicUsize>,
}

impl MonitoredDevice {
    /// A device building on `threads` threads (`threads=N`), whose memory monitor adds every
    /// reported allocation (`bytes > 0`) and free (`bytes < 0`); the running sum's maximum is
    /// the device's high-water mark. An allocation that would take the device's bytes beside
    /// Rust's heap past the memory budget ([`room_for`]) is refused: Embree then cancels the
    /// build with `RTC_ERROR_OUT_OF_MEMORY`, and [`MonitoredDevice::refused_at`] says so. A
    /// refusal before the allocation (`post == false`) is not counted, one after it is (Embree
    /// frees it later), as Embree's documentation of the callback asks.
    pub fn new(threads: usize) -> Result<MonitoredDevice, embree3::Error> {
        let device = Device::with_config(Config {
            threads: u32::try_from(threads.max(1)).unwrap_or(u32::MAX),
            ..Config::default()
        })?;
        let held = Arc::new(AtomicIsize::new(0));
        let peak = Arc::new(AtomicIsize::new(0));
        let refused_at = Arc::new(AtomicUsize::new(0));
        let (tally, high) = (Arc::clone(&held), Arc::clone(&peak));
        let refused = Arc::clone(&refused_at);
        device.set_memory_monitor_function(move |bytes, post| {
            let now = tally.fetch_add(bytes, Ordering::Relaxed) + bytes;
            if bytes > 0 && !room_for(now.max(0) as usize) {
                refused.fetch_max(now.max(1) as usize, Ordering::Relaxed);
                if !post {
                    tally.fetch_sub(bytes, Ordering::Relaxed);
                }
                return false;
            }
            high.fetch_max(now, Ordering::Relaxed);
            true
        });
        Ok(MonitoredDevice {
            device,
            held,
            peak,
            refused_at,
        })
    }

    /// The device's bytes (Embree's alone) at the allocation the memory budget refused, if one
    /// was refused.
    pub fn refused_at(&self) -> Option<usize> {
        Some(self.refused_at.load(Ordering::Relaxed)).filter(|&b| b > 0)
    }

    /// Bytes allocated and not yet freed through this device so far.
    pub fn held_bytes(&self) -> usize {
        self.held.load(Ordering::Relaxed).max(0) as usize
    }

    /// The most bytes this device held at once so far.
    pub fn peak_bytes(&self) -> usize {
        self.peak.load(Ordering::Relaxed).max(0) as usize
    }
}
