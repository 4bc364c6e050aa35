//! An Embree device with a build thread count and a memory-monitor callback that tallies what
//! Embree holds.

use embree3::{Config, Device};
use std::sync::Arc;
use std::sync::atomic::{AtomicIsize, Ordering};

/// A device, the running sum of the bytes its memory monitor reported and that sum's maximum.
pub(super) struct MonitoredDevice {
    pub device: Device,
    held: Arc<AtomicIsize>,
    peak: Arc<AtomicIsize>,
}

impl MonitoredDevice {
    /// A device building on `threads` threads (`threads=N`), whose memory monitor adds every
    /// reported allocation (`bytes > 0`) and free (`bytes < 0`). The callback never cancels, so
    /// every reported allocation happens (Embree's rule for what to count); the running sum's
    /// maximum is the device's high-water mark.
    pub fn new(threads: usize) -> Result<MonitoredDevice, embree3::Error> {
        let device = Device::with_config(Config {
            threads: u32::try_from(threads.max(1)).unwrap_or(u32::MAX),
            ..Config::default()
        })?;
        let held = Arc::new(AtomicIsize::new(0));
        let peak = Arc::new(AtomicIsize::new(0));
        let (tally, high) = (Arc::clone(&held), Arc::clone(&peak));
        device.set_memory_monitor_function(move |bytes, _post| {
            let now = tally.fetch_add(bytes, Ordering::Relaxed) + bytes;
            high.fetch_max(now, Ordering::Relaxed);
            true
        });
        Ok(MonitoredDevice { device, held, peak })
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
