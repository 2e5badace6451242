"""User-facing errors: reported as one line on stderr with a non-zero exit."""


class UserError(Exception):
    """Bad input from the user (file, dimensions, scene, option). Never a bug."""
