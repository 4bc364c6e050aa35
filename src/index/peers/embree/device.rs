//! An Embree device with a build thread count and a memory-monitor callback that tallies what
//! Embree holds.

use embree3::{Config, Device};
use std::sync::Arc;
use std::sync::atomic::{AtomicIsize, Ordering};

/// A device and the running sum of the bytes its memory monitor reported.
pub(super) struct MonitoredDevice {
    pub device: Device,
    held: Arc<AtomicIsize>,
}

impl MonitoredDevice {
    /// A device building on `threads` threads (`threads=N`), whose memory monitor adds every
    /// reported allocation (`bytes > 0`) and free (`bytes < 0`). The callback never cancels, so
    /// every reported allocation happens (Embree's rule for what to count).
    pub fn new(threads: usize) -> Result<MonitoredDevice, embree3::Error> {
        let device = Device::with_config(Config {
            threads: u32::try_from(threads.max(1)).unwrap_or(u32::MAX),
            ..Config::default()
        })?;
        let held = Arc::new(AtomicIsize::new(0));
        let tally = Arc::clone(&held);
        device.set_memory_monitor_function(move |bytes, _post| {
            tally.fetch_add(bytes, Ordering::Relaxed);
            true
        });
        Ok(MonitoredDevice { device, held })
    }

    /// Bytes allocated and not yet freed through this device so far.
    pub fn held_bytes(&self) -> usize {
        self.held.load(Ordering::Relaxed).max(0) as usize
    }
}
