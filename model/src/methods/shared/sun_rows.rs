//! The rows a fit computes on the CPU for each batch and the sun at the camera
//! (`BatchRows`, read on the GPU as `batches[layer].model`), kept by its CPU twin for the last
//! sun it was asked about: every direction of an image shares the sun.

use super::{BatchRows, Params};
use std::sync::{Arc, Mutex};

/// A function giving batch `layer`'s rows for the sun at zenith cosine `mu_s`.
pub type RowsFn = fn(&Params, usize, f64) -> BatchRows;

/// Every batch's rows for the last sun asked for.
#[derive(Debug, Default)]
pub struct SunRows {
    last: Mutex<Option<(f64, Arc<Vec<BatchRows>>)>>,
}

impl SunRows {
    /// The rows of every batch of `p` by `rows` with the sun at zenith cosine `mu_s`, computed
    /// again only when the sun changed.
    pub fn get(&self, p: &Params, rows: RowsFn, mu_s: f64) -> Arc<Vec<BatchRows>> {
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((at, kept)) = last.as_ref()
            && *at == mu_s
        {
            return kept.clone();
        }
        let all: Arc<Vec<BatchRows>> = Arc::new(
            (0..p.batches.len())
                .map(|layer| rows(p, layer, mu_s))
                .collect(),
        );
        *last = Some((mu_s, all.clone()));
        all
    }
}
