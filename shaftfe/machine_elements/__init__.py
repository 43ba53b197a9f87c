"""The seed's machine-element checks beside the shaft (seed 000 §8.2): parallel keys
(``key``), the drive's gear pair (``gear``) and the bearings' life over the duty cycle
(``bearings``). Inputs in ``geometry/common/elements.toml``; each function is pure."""
