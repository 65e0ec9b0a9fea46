"""The data file of one run, as bytes: NPY (the measured vibration, float32 samples x 3) or
HDF5 (both vibration channels and the label time lines). The same run gives the same bytes."""
import io
import json

import numpy as np


def encode_npy(result):
    buffer = io.BytesIO()
    np.save(buffer, np.ascontiguousarray(result['vibration']), allow_pickle=False)
    return buffer.getvalue()


def encode_hdf5(result, parameters):
    import h5py  # only campaigns that ask for HDF5 need it
    buffer = io.BytesIO()
    labels = result['labels']
    # No creation times: the file must not depend on when it was written.
    with h5py.File(buffer, 'w', libver='earliest', track_order=False) as f:
        for name, data in (('vibration', result['vibration']), ('vibration_ideal', result['vibration_ideal']),
                           ('label_time_s', labels['time_s']), ('label_ring_speed_rad_s', labels['ring_speed_rad_s']),
                           ('label_ring_angle_rad', labels['ring_angle_rad']), ('label_load', labels['load'])):
            f.create_dataset(name, data=np.ascontiguousarray(data), track_times=False)
        f.attrs['label_phase'] = json.dumps(labels['phase'])
        f.attrs['label_defects'] = json.dumps(labels['defects'], sort_keys=True)
        f.attrs['parameters'] = json.dumps(parameters, sort_keys=True, default=str)
        f.attrs['info'] = json.dumps(result['info'], sort_keys=True)
    return buffer.getvalue()


# The manifest's label columns, in this order (the keys of run_labels).
LABEL_NAMES = ('defects_at_end', 'mean_radial_load_N', 'mean_ring_speed_rad_s', 'sample_rate_hz', 'samples',
               'spall_depth_at_end_m', 'spall_width_at_end_m')


def run_labels(result):
    """Labels of the whole run for the manifest: the defects at its end and mean operating point."""
    labels = result['labels']
    last = labels['defects'][-1] if labels['defects'] else []
    load = np.asarray(labels['load'])
    return {
        'defects_at_end': '+'.join(sorted(d['surface'] for d in last)) or 'none',
        'spall_width_at_end_m': max((d['width_m'] for d in last), default=0.0),
        'spall_depth_at_end_m': max((d['depth_m'] for d in last), default=0.0),
        'mean_ring_speed_rad_s': float(np.mean(labels['ring_speed_rad_s'])) if len(load) else 0.0,
        'mean_radial_load_N': float(np.mean(np.hypot(load[:, 0], load[:, 1]))) if len(load) else 0.0,
        'samples': int(result['info']['measured_samples']),
        'sample_rate_hz': float(result['info']['measured_rate_hz']),
    }
