"""The in-memory form of every image tirpol reads, renders or reduces."""


class Image(dict):
    """Channels in order: name → float32 numpy array of shape (H, W) (row-major, origin top-left),
    plus ``attributes``, the EXR header attributes (int, float, str or list of floats: units,
    band, polarizer angles, ...). A plain ``dict`` of arrays is accepted wherever an Image is."""

    def __init__(self, channels=(), attributes=None):
        super().__init__(channels)
        self.attributes = dict(attributes or {})

    @property
    def shape(self):
        """(H, W) of the channels; ``None`` for an image without channels."""
        for array in self.values():
            return array.shape
        return None

    def __repr__(self):
        return f"tirpol.Image(shape={self.shape}, channels={list(self)}, attributes={sorted(self.attributes)})"
