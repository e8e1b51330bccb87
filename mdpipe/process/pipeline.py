"""One capture from file to feature rows: detect, follow, combine, analyse, classify."""

import functools
from dataclasses import replace

import numpy as np

from mdpipe.errors import ParameterError
from mdpipe.io import open_capture
from mdpipe.io.iq import is_iq_recording
from mdpipe.process import (combs, flashes, images, impulses, interference, memory, ranging, saturation, selection,
                            transmitters)
from mdpipe.process.classify import classify
from mdpipe.process.cw import process_recording
from mdpipe.process.features import RangeTrack, analyse_target
from mdpipe.process.result import CaptureResult, base_row
from mdpipe.process.filters import least_squares_line

MIN_CHIRPS = 64
TRACK_POINTS = 256  # range track points kept per target (for its range rate and extent)
SAME_TRACK_BINS = 1.5  # two detections whose tracks are this close on average (range bins) are one target
HUB_FIXED_BINS = 1.0   # a drone's hub between its range-Doppler images moving less over the dwell is held at one range


def target_tracks(stats, detections, process, n_samples):
    """Each detection's fractional range track (padded-grid bins per chirp) and the chunks it spends in
    each gate bin, less the detections whose track follows a stronger one's (the same target: a mover's
    mean power peaks at several bins along its path, and each is followed onto the same track).

    Returns
    -------
    list of (detection, track_bins (n_chirps,), visits (B,))
    """
    kept = []
    for detection in detections:  # strongest first
        track_bins, visits = selection.chirp_track(stats, detection, window=process.range_window,
                                                   n_samples=n_samples, zero_pad=process.zero_pad)
        if all(np.mean(np.abs(track_bins - other)) >= SAME_TRACK_BINS * process.zero_pad for _, other, _ in kept):
            kept.append((detection, track_bins, visits))
    return kept


def target_signals(reader, stats, tracks, process):
    """Pass 2: each target's slow time along its fractional range track (:func:`target_tracks`).

    The channels are combined with one weight vector per target, the dominant eigenvector of the
    moving covariance summed over the bins it visits (chunk-weighted): one spatial signature, so
    no weight change along the track.

    Returns
    -------
    list of (:class:`~mdpipe.process.features.RangeTrack`, signal (n_chirps,) complex, rx_gain_db, weight (C,))
    """
    weights, gains = [], []
    for _, _, visits in tracks:
        weight, gain = selection.channel_weights(np.tensordot(visits, stats.covariance, axes=1)[None])
        weights.append(weight[0])
        gains.append(float(gain[0]))
    bins = np.array([track_bins for _, track_bins, _ in tracks])
    signals = ranging.slow_time(reader, bins, np.array(weights), window=process.range_window,
                                zero_pad=process.zero_pad, dtype=process.dtype, all_bins=process.range_bins == "all")
    params = reader.params
    every = max(1, stats.n_chirps // TRACK_POINTS)
    t_s = np.arange(0, stats.n_chirps, every) / params.prf_hz
    return [(RangeTrack(t_s=t_s, range_m=ranging.bin_range_m(track_bins[::every], params, process.zero_pad),
                        bin_m=params.range_bin_m, coupling_m_per_hz=params.sampled_duration_s * params.range_bin_m),
             signals[:, i], gain, weight)
            for i, (track_bins, gain, weight) in enumerate(zip(bins, gains, weights))]


def flash_views(reader, track_bins, weight, process):
    """A cached callable: the target's :class:`~mdpipe.process.ranging.FlashViews` (``flashes.RAMP_PARTS`` parts of
    every ramp, and the range sides ``flashes.SIDE_BINS`` bins off its track), read from the open capture on its
    first call only: the features ask for it only where a path reads the echo's power period or flash times stay
    ambiguous (one more pass over the capture)."""
    return functools.cache(lambda: ranging.flash_views(reader, track_bins, weight, segments=flashes.RAMP_PARTS,
                                                       side_bins=flashes.SIDE_BINS * process.zero_pad,
                                                       window=process.range_window, zero_pad=process.zero_pad,
                                                       chunk_chirps=process.chunk_chirps))


def flank_views(reader, track_bins, weight, process, common=None):
    """A cached callable: the target's :class:`~mdpipe.process.ranging.Flanks`, the power of its range flanks
    (:func:`mdpipe.process.ranging.flank_powers`, over :func:`mdpipe.process.ranging.flank_bins`) beside ``common``
    (the capture's common mode per chirp), read on its first call only; None where a short ramp keeps the flashes in
    the target's own bin and its sides (:func:`flash_views`)."""
    bins = ranging.flank_bins(reader.params, process.range_window)
    if bins is None:
        return None
    return functools.cache(lambda: ranging.Flanks(
        ranging.flank_powers(reader, track_bins, weight, inner_bins=bins[0], outer_bins=bins[1],
                             window=process.range_window, zero_pad=process.zero_pad, chunk_chirps=process.chunk_chirps),
        common, ranging.flank_leak_db(process.range_window, reader.params.n_samples, *bins)))


def analysed_row(reader, detection, target, track_bins, *, process, noise_power, base, capture_notes, undisturbed=True,
                 common=None):
    """One target's row (``base()`` filled in: range, features, class and notes) and its analysis, from its
    ``detection``, ``target`` (:func:`target_signals`: range track, slow time, RX gain, RX weights) and per-chirp
    ``track_bins``; ``undisturbed``: no bursts of another radar light every bin at once and no samples clip, so that
    its range flanks may be read (:func:`flank_views`, beside the capture's ``common`` mode per chirp) and a chopping
    read again on the ramp's parts (the bursts fall in some parts of some ramps, again and again)."""
    params = reader.params
    track, signal, rx_gain_db, weight = target
    analysis = analyse_target(signal, prf_hz=params.prf_hz, wavelength_m=params.wavelength_m, noise_power=noise_power,
                              params=process, track=None if detection.fixed_bin is not None else track,  # fixed: no track
                              flash_views=flash_views(reader, track_bins, weight, process),
                              ramp_share=params.sampled_duration_s / params.chirp_period_s, reread=undisturbed,
                              flanks=flank_views(reader, track_bins, weight, process, common) if undisturbed else None)
    row = base()
    row.update(range_m=detection.range_m, range_bin=int(detection.bin), range_min_m=float(track.range_m.min()),
               range_max_m=float(track.range_m.max()), rx_gain_db=rx_gain_db)
    row.update(analysis.row)
    label, reason = classify(row, detected=True)
    row["class"] = label
    row["notes"] = "; ".join([f"class: {reason}"] + analysis.notes + capture_notes)
    return row, analysis


def hub_target(reader, stats, owner, image, process, analyse):
    """The drone whose range-Doppler images are the targets ``owner`` and ``image`` (each a :func:`target_tracks`
    entry), analysed at its hub, midway between them: (detection, target, row, analysis), ``analyse`` giving the
    row and analysis (:func:`analysed_row`). One more pass over the capture, for its slow time.

    Each image's track follows its own side's flashes as they brighten and fade (the two images of a hovering 3-blade
    quadrotor at 94 GHz drifted 0.9 bin over 0.55 s), and a track that wanders splatters the slow time's spectrum.
    The hub is followed along the least-squares straight line through the midpoints of their tracks (a constant range
    rate) where that moves more than ``HUB_FIXED_BINS`` over the dwell, else held at its mean: a fixed bin holds a
    target within half a bin of it."""
    (_, first_bins, first_visits), (_, second_bins, second_visits) = owner, image
    midpoints = (first_bins + second_bins) / 2
    line = least_squares_line(np.arange(len(midpoints), dtype=np.float64), midpoints)
    hub_bin = float(line.mean())
    detection = selection.detection_at(stats, hub_bin,
                                       range_m=float(ranging.bin_range_m(hub_bin, reader.params, process.zero_pad)))
    if abs(line[-1] - line[0]) > HUB_FIXED_BINS * process.zero_pad:
        detection, track_bins = replace(detection, fixed_bin=None), line  # followed
    else:
        track_bins = np.full_like(line, hub_bin)
    target = target_signals(reader, stats, [(detection, track_bins, first_visits + second_visits)], process)[0]
    return (detection, target, *analyse(detection, target, track_bins))


def without_images(detections, targets, rows, analyses, params, hub=None, crossed=False, clipped=False):
    """The four per-target lists less the targets that are a stronger drone's range-Doppler image
    (:func:`mdpipe.process.images.image_owners` by their combs, :func:`mdpipe.process.images.flash_image_owners` by
    their flashes; not where bursts of another radar cross ours, ``crossed``, nor where samples are ``clipped``: the
    bursts light every bin at once, and a clipped echo's images carry its power's swings to other bins), noted on that
    drone's row; the rows renumbered.

    A drone seen only as images (:func:`mdpipe.process.images.seen_from_a_side`) is analysed at its hub by
    ``hub(owner, image)`` (indices; None: not analysed again), and that row replaces the stronger image's where it
    is a drone's: each image holds one side's blade flashes, the approaching blades' or the receding ones', so that
    its flashes repeat once per chopping period whatever the blade count (a 3-blade quadrotor at 94 GHz read at
    half its chopping frequency, its flashes taken for an odd count's two per period). A target detected at that hub
    with a body line (:func:`mdpipe.process.images.hubs_between`) owns the images where it reads a drone, and is
    replaced by the drone analysed at the hub where it reads otherwise: one row a drone."""
    reach_m = images.image_reach_m(params)
    by_combs = images.image_owners(rows, reach_m=reach_m)
    told = images.FlashImages(by_combs) if crossed or clipped else images.flash_image_owners(
        rows, [np.abs(target[1]) ** 2 for target in targets], by_combs, reach_m=reach_m,
        longest_chirps=params.prf_hz / combs.MIN_CHOP_HZ)
    owners, hubs = images.hubs_between(rows, told.owners, reach_m=reach_m)
    rows, detections, targets, analyses = list(rows), list(detections), list(targets), list(analyses)
    by_comb = {i for i, owner in enumerate(by_combs) if owner is not None} | {o for o in by_combs if o is not None}
    groups = {}
    for image, owner in enumerate(owners):
        if owner is not None:
            groups.setdefault(owner, []).append(image)
    for owner, group in groups.items():
        place, notes, moved = owner, [], False
        for image in group:
            how = None if image in by_comb else images.BY_TURNS if image in told.by_turns else images.AT_ONCE
            note = images.image_note(rows[image], reach_m=reach_m, by_flashes=how)
            if hub is not None and not moved and images.seen_from_a_side(rows[owner]):
                detection, target, row, analysis = hub(owner, image)
                if row["class"] == "drone":
                    note = images.hub_note(rows[owner], rows[image], reach_m=reach_m, by_flashes=how)
                    place, moved = hubs.get(owner, owner), True
                    detections[place], targets[place], rows[place], analyses[place] = detection, target, row, analysis
            notes.append(note)
        if place != owner:  # the drone analysed at its images' hub stands in for the target detected there
            owners[owner] = place
            for image in group:
                owners[image] = place
        rows[place]["notes"] += "".join("; " + note for note in notes)
    kept = [i for i, owner in enumerate(owners) if owner is None]
    rows = [rows[i] for i in kept]
    for index, row in enumerate(rows):
        row["target"] = index
    return [detections[i] for i in kept], [targets[i] for i in kept], rows, [analyses[i] for i in kept]


def clipped_share(reader, stats):
    """The share of the samples read in pass 1 at the int16 full scale; None for float samples (no full scale)."""
    return stats.clipped_fraction if reader.layout.sample_dtype == "int16" else None


def _base_row(path, stats, process, params, clipped, common, cycle):
    return base_row(path, process, params, n_samples=stats.n_chirps, clipped=clipped, interference=common.spike_share,
                    transmitters=cycle.cycle)


def no_detection_note(test, process):
    """Why nothing was detected: the strongest line and band against their thresholds (dB over the noise)."""
    return (f"no moving target above the noise in {process.min_range_m:g}-{process.max_range_m:g} m at a false-alarm "
            f"probability of {test.false_alarm_probability:g} per capture ({test.shortfall()})")


def check_readable(reader, process, path):
    """Refuse a capture too short to analyse, needing more memory than allowed, or whose range gate holds too few
    bins (before pass 0 reads a chirp, and again once one transmitter's chirps are selected)."""
    if reader.n_chirps < MIN_CHIRPS:
        raise ParameterError(f"{path}: {reader.n_chirps} chirp(s){' of one transmitter' if reader.stride > 1 else ''}; "
                             f"the analysis needs at least {MIN_CHIRPS}")
    memory.check_memory(reader, process)
    n_gate = memory.gate_bin_counts(reader.params, process)[1]  # known before pass 1: an empty gate cannot crash it
    if n_gate < 3:
        raise ParameterError(f"{path}: the range gate [{process.min_range_m:g}, {process.max_range_m:g}] m holds "
                             f"{n_gate} bin(s) of {reader.params.range_bin_m:.3g} m; widen it")


def transmit_cycle(reader, process, path):
    """The chirps' :class:`~mdpipe.process.transmitters.TransmitCycle` (``--transmitters``, the file's ``TxSeq``, else
    a cycle of two found on the static echoes in pass 0) and pass 0's :class:`~mdpipe.process.interference.CommonMode`,
    over the first transmitter's chirps, which ``reader`` then reads (pass 0 read again where a cycle was found)."""
    given = process.transmitters_given
    cycle = transmitters.TransmitCycle(given, "given") if given else transmitters.from_file(reader.tx_sequence)
    if cycle is not None and cycle.cycle > 1:
        reader.select_every(cycle.cycle)
    check_readable(reader, process, path)
    sums = None if cycle is not None else transmitters.PhaseSums(reader.params.n_samples)
    common = interference.common_mode(reader, window=process.range_window, phase_sums=sums)
    if cycle is not None:
        return cycle, common
    test = transmitters.cycle_test(sums)
    if test is None or not test.found:
        return transmitters.TransmitCycle(1, "single", test), common
    reader.select_every(test.cycle)
    check_readable(reader, process, path)
    return transmitters.TransmitCycle(test.cycle, "found", test), interference.common_mode(reader,
                                                                                           window=process.range_window)


def process_capture(path, process, *, frame_counter="auto", overrides=None, allow_external=False):
    """Analyse one capture; returns a :class:`CaptureResult`.

    An I/Q recording of a CW radar (:func:`mdpipe.io.iq.is_iq_recording`) is analysed by
    :func:`mdpipe.process.cw.process_recording` instead.

    Raises :class:`mdpipe.errors.CaptureFormatError` for unreadable files and
    :class:`mdpipe.errors.ParameterError` when the capture is too short to analyse, needs more memory
    than ``process.max_memory_gb`` or holds no signal.
    """
    if is_iq_recording(path):
        if frame_counter is True:
            raise ParameterError(f"{path}: an I/Q (CW) recording has no chirps and no frame counter; drop "
                                 "--frame-counter yes")
        return process_recording(path, process, overrides=overrides, allow_external=allow_external)
    with open_capture(path, frame_counter=frame_counter, overrides=overrides,
                      allow_external=allow_external) as reader:
        cycle, common = transmit_cycle(reader, process, path)
        params = reader.params
        max_range_m = min(process.max_range_m, params.max_range_m)
        stats = ranging.gate_statistics(reader, window=process.range_window, zero_pad=process.zero_pad,
                                        min_range_m=process.min_range_m, max_range_m=max_range_m,
                                        chunk_chirps=process.chunk_chirps)
        if reader.constant_description():
            raise ParameterError(f"{path}: {reader.constant_description()}; the recording holds no signal")
        test = None
        if process.range_m is not None:
            detections = [selection.manual_detection(stats, process.range_m, gate_m=(process.min_range_m, max_range_m),
                                                     params=params, zero_pad=process.zero_pad)]
        else:
            test = selection.detection_test(stats, false_alarm_probability=process.false_alarm_probability)
            detections = selection.detect(stats, test, max_targets=process.max_targets, zero_pad=process.zero_pad)
        noise = selection.noise_power(stats) / params.n_channels
        capture_notes = list(reader.warnings) + [n for n in (cycle.note(params),) if n]
        clipped = clipped_share(reader, stats)
        if clipped:
            capture_notes.append(f"{clipped:.2%} of the samples sit at the int16 full scale (clipped): "
                                 "amplitudes and spectra are distorted")
        if common.crossed:
            capture_notes.append(f"{common.spike_share:.2%} of the chirps hold a burst lighting most range bins at once "
                                 "(another radar's chirps crossing ours)")
        rows, analyses = [], []
        if not detections:
            row = _base_row(path, stats, process, params, clipped, common, cycle)
            row["notes"] = "; ".join([no_detection_note(test, process)] + capture_notes)
            return CaptureResult(str(path), params, reader.layout.describe(), stats, [], [], [row],
                                 noise_power=noise, process=process, detection_test=test)
        tracks = target_tracks(stats, detections, process, params.n_samples)
        detections = [detection for detection, _, _ in tracks]
        targets = target_signals(reader, stats, tracks, process)
        layout = reader.layout.describe()
        analyse = functools.partial(analysed_row, reader, process=process, noise_power=noise,
                                    base=lambda: _base_row(path, stats, process, params, clipped, common, cycle),
                                    capture_notes=capture_notes, undisturbed=not (common.crossed or clipped),
                                    common=common.series)
        for index, (detection, target, (_, track_bins, _)) in enumerate(zip(detections, targets, tracks)):
            row, analysis = analyse(detection, target, track_bins)
            row["target"] = index
            rows.append(row)
            analyses.append(analysis)
        detections, targets, rows, analyses = without_images(
            detections, targets, rows, analyses, params,
            hub=lambda owner, image: hub_target(reader, stats, tracks[owner], tracks[image], process, analyse),
            crossed=common.crossed, clipped=bool(clipped))
        levels_db = [detection.snr_db if row["snr_db"] is None else row["snr_db"]
                     for detection, row in zip(detections, rows)]
        rows = saturation.saturated_rows(rows, levels_db, clipped, capture_notes)
        signals = [signal for _, signal, _, _ in targets]
        rows = interference.crossed_rows(rows, signals, common, capture_notes)
        rows = impulses.impulsive_rows(rows, signals, noise, capture_notes)
    return CaptureResult(str(path), params, layout, stats, detections, analyses, rows, noise_power=noise,
                         process=process, detection_test=test)
