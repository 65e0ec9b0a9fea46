"""The error of a bad campaign file or output directory (the command exits 2 on it)."""


class CampaignError(ValueError):
    """A campaign file or output directory that cannot be used; the message names the file and the key."""
