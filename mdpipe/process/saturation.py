"""ADC saturation: what samples clipped at the int16 full scale do to a capture's rows.

Clipping is a memoryless nonlinearity on the IF samples. The beat of a strong scatterer gains harmonics (``3 f_b``: a
copy of the echo at three times its range, folded at the maximum range) and, mixed with the other scatterers of the
scene (static clutter too), intermodulation products (``2 f_a - f_b``, ...): copies of a target's echo at other ranges,
its slow-time phase multiplied by a whole number (its Doppler mirrored or scaled), its periodicities (blade flashes,
wingbeat) intact. Each is detected as one more target and read as one more drone or bird. Measured
(``benchmarks/bench_impairments.py``: the bundled samples and 24 default-sweep scenes, their IF scaled until a share
``s`` of the samples clip): images from ``s`` = 0.1 % on (3 at 0.1 %, 34 at 3 %, 57 at 50 %, of 28 captures), a third
to two thirds of them read drone or bird, the highest 53.7, 31.9, 21.0, 13.6 and 3.5 dB under its target at 0.1, 1,
3, 10 and 30 %: under ``20 log10(s) + 9.5`` dB. The targets' own values stayed within 3 % of their unclipped reading
(or were withheld for their own reasons) up to 50 %.

So, in a capture whose samples clip: a detection under the capture's strongest by more than clipping's images reach
(:func:`image_ceiling_db`) may be an image. It is read as ``none``, every feature but its SNR withheld as
``clipping_image``; a genuine weaker target of an overdriven capture is withheld with them (the capture does not tell
them apart; lower the receiver gain).
"""

import numpy as np

from mdpipe.process.features import read_as, withheld_row

IMAGE_MARGIN_DB = 16.0  # images stood at most 20 log10(s) + 9.5 dB under their target (s = 0.1 % - 50 %): 6 dB more


def image_ceiling_db(clipped_share):
    """The level (dB under the capture's strongest detection, <= 0) that clipping's images reach at most when a share
    ``clipped_share`` (> 0) of the samples clip: ``20 log10(s) + IMAGE_MARGIN_DB`` (their amplitude grows as the share
    of the time the IF spends beyond the full scale)."""
    return min(0.0, 20.0 * np.log10(clipped_share) + IMAGE_MARGIN_DB)


def _image_row(row, strongest, *, level_db, clipped_share, capture_notes):
    """``row`` as a possible image of the detection ``strongest`` (a row): class ``none``, every feature withheld but
    its SNR, its notes the why and ``capture_notes``."""
    ceiling_db = image_ceiling_db(clipped_share)
    note = (f"class: possibly an image of the target at {strongest['range_m']:.4g} m made by clipping: "
            f"{clipped_share:.2%} of the samples sit at the int16 full scale, and this echo stands {-level_db:.1f} dB "
            f"under that target, within the {-ceiling_db:.1f} dB clipping's harmonics and intermodulation reach; "
            f"{read_as(row)}; lower the receiver gain")
    return withheld_row(row, status="clipping_image", note=note, capture_notes=capture_notes)


def saturated_rows(rows, snr_db, clipped_share, capture_notes=()):
    """The target rows of one capture (``snr_db``: each target's SNR along its track, dB) read for its share of clipped
    samples (None: float samples, no full scale known); ``capture_notes``: the capture's warnings, kept in an image's
    notes. Returns new rows; without clipping, ``rows`` as they are."""
    if not clipped_share or not rows:
        return rows
    strongest = int(np.argmax(snr_db))
    ceiling_db = image_ceiling_db(clipped_share)
    out = []
    for index, (row, snr) in enumerate(zip(rows, snr_db)):
        level_db = float(snr - snr_db[strongest])
        if index != strongest and level_db <= ceiling_db:
            row = _image_row(row, rows[strongest], level_db=level_db, clipped_share=clipped_share,
                             capture_notes=capture_notes)
        out.append(row)
    return out
