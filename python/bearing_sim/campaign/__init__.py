"""Dataset campaigns: N labelled runs of a scenario template with parameters drawn from
distributions, one file per run and a manifest, resumable, on Dask distributed
(docs/datasets.md, "Campaigns")."""
from .errors import CampaignError  # noqa: F401
from .execute import parse_index_range, run_campaign, run_index  # noqa: F401
from .spec import Campaign  # noqa: F401
