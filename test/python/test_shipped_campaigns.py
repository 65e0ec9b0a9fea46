"""The shipped campaign files (config/campaigns): each loads and its template check passes (a
run of it loads its scenario, bearing and sensor); config/campaigns/cwru_rig.yaml gives the
labels and the channel docs/datasets.md promises, on one generated run per class."""
import json

import numpy as np
import pytest
import yaml

from bearing_sim.campaign import Campaign
from bearing_sim.campaign.execute import check_template, run_index
from conftest import SOURCE

CAMPAIGNS = sorted((SOURCE / 'config' / 'campaigns').glob('*.yaml'))
CWRU_RIG = SOURCE / 'config' / 'campaigns' / 'cwru_rig.yaml'
CWRU_SENSOR = SOURCE / 'config' / 'sensors' / 'cwru_drive_end_accelerometer.yaml'
FILE_SENSOR = yaml.safe_load(CWRU_SENSOR.read_text(encoding='utf-8'))['sensor']


@pytest.mark.parametrize('path', CAMPAIGNS, ids=[p.name for p in CAMPAIGNS])
def test_shipped_campaign_loads_and_passes_its_template_check(path):
    campaign = Campaign.load(str(path))
    check_template(campaign, iter(range(campaign.count)))  # raises a CampaignError naming the key


def first_run_of_each_class(campaign, classes):
    found = {}
    for i in range(campaign.count):
        defects = campaign.parameters_of(i)['defects']
        label = defects[0]['surface'] if defects else 'none'
        found.setdefault(label, i)
        if len(found) == len(classes):
            return found
    raise AssertionError(f'classes drawn: {sorted(found)}')


def test_cwru_rig_runs_are_labelled_none_inner_ball_outer_with_the_drive_end_sensor_in_m_s2(tmp_path):
    text = CWRU_RIG.read_text(encoding='utf-8')
    campaign = Campaign(text, str(CWRU_RIG))
    classes = ('none', 'inner_race', 'ball', 'outer_race')
    for label, index in first_run_of_each_class(campaign, classes).items():
        run = campaign.definition(index)
        sensor = yaml.safe_load(run.derived_files['sensor_file'][1])['sensor']
        assert sensor['output_unit'] == 'm_s2' and sensor['axis'] == [-1.0, 0.0, 0.0]  # positive up
        # The path's resonances are the run's draws, each within 5 % of the sensor file's.
        drawn = run.parameters
        assert sensor['mount_resonance_Hz'] == drawn['mount_resonance_Hz']
        assert abs(sensor['mount_resonance_Hz'] / FILE_SENSOR['mount_resonance_Hz'] - 1.0) <= 0.05
        modes = sensor['path_modes']
        assert [m['frequency_Hz'] for m in modes] == [drawn[f'path_mode_{k}_Hz'] for k in range(1, len(modes) + 1)]
        for mode, measured in zip(modes, FILE_SENSOR['path_modes']):
            assert abs(mode['frequency_Hz'] / measured['frequency_Hz'] - 1.0) <= 0.05
            assert mode['damping_ratio'] == measured['damping_ratio']
        # The assembly's balance: the two low modes scaled alike within 0.27-1.16 x the file's, the
        # 5.2 kHz mode the file's, the 2.9 kHz mode the rest, so that the modes add up to 1 (the
        # file's do) to the rounding of three decimals.
        file_modes = FILE_SENSOR['path_modes']
        scale = [modes[k]['participation'] / file_modes[k]['participation'] for k in (0, 1)]
        assert 0.27 - 0.01 <= scale[0] <= 1.16 + 0.01 and abs(scale[1] / scale[0] - 1.0) < 0.02
        assert modes[3]['participation'] == file_modes[3]['participation']
        assert abs(sum(m['participation'] for m in modes) - sum(m['participation'] for m in file_modes)) <= 0.002
        # The EDM pits are round with a recast rim 0.1 mm wide, its height the run's draw within
        # a factor 2 of the bearing file's 1 um.
        imperfections = yaml.safe_load(run.derived_files['bearing_file'][1])['imperfections']
        assert imperfections['spall_pits'] == 'round' and imperfections['spall_rim_width_um'] == 100.0
        assert imperfections['spall_rim_height_um'] == drawn['rim_height_um']
        assert 0.5 <= drawn['rim_height_um'] <= 2.0
        assert imperfections['ball_spall_latitude_deg'] == drawn['ball_spall_latitude_deg']
        record = run_index(str(CWRU_RIG), text, str(tmp_path), index)
        assert record['status'] == 'ok', record.get('error')
        labels = record['labels']
        assert labels['defects_at_end'] == label
        assert labels['sample_rate_hz'] == 12000.0 and labels['samples'] >= 12000
        rpm = labels['mean_ring_speed_rad_s'] * 60.0 / (2.0 * np.pi)
        assert 1715.0 <= rpm <= 1800.0  # the set's 0-3 hp speeds
        vibration = np.load(tmp_path / record['file'])
        assert vibration.shape == (labels['samples'], 3)
        # Channel 0 in m/s^2, not g or V: at least the sensor noise (10 ug/sqrt(Hz) over the
        # 4.8 kHz band: 7e-4 g), at most what the largest fault gives (real records: < 0.7 g).
        rms_g = float(np.std(vibration[-12000:, 0])) / 9.80665
        assert 1e-4 < rms_g < 10.0, rms_g
        status = json.loads((tmp_path / 'runs' / f'run_{index:07d}.json').read_text())
        assert status['parameters']['defects'] == run.parameters['defects']


def test_cwru_rig_ball_pits_lie_at_the_latitudes_of_a_spot_at_random_on_a_sphere():
    """Where the assembly left the ball's pit (docs/model.md 9.5): a spot at random on a sphere
    has a latitude whose sine is uniform (equal-height zones have equal areas), so the
    campaign's equally likely choices are the midpoints of n equal bins of the sine. Rounded to
    0.1 deg, each sine is off by at most 0.05 deg x pi / 180 < 0.001."""
    spec = yaml.safe_load(CWRU_RIG.read_text(encoding='utf-8'))['parameters']['ball_spall_latitude_deg']
    latitudes = sorted(spec['choice'])
    n = len(latitudes)
    assert n >= 10
    for k, degrees in enumerate(latitudes):
        assert abs(np.sin(np.radians(degrees)) - (k + 0.5) / n) < 1e-3, (k, degrees)
