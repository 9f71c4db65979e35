"""Physics core: closed-form motion, continuous contact detection, batched fixed-step engine."""
