"""habuffer: the coherent Robin Hood hash of per-pixel fragment lists.

The CPU containers of every technique (Buffer, build), the statistics
experiments and the harness as tables of numpy arrays (Table), the spatial
hash (SpatialHash), and the GPU path where a headless EGL context can be
made. Errors carry the library's messages: ValueError for bad arguments,
TypeError for wrong dtypes, IndexError for pixels off the screen, DataError,
SceneError and GlError for files, scenes and OpenGL.

    import habuffer as hb
    buf = hb.build(xy, depth, rgba, screen=(64, 64), lossless=True)
    offsets, codes, rgba, ages = buf.lists()
"""

from ._habuffer import (  # noqa: F401
    FRAGMENT_DTYPE,
    Buffer,
    DataError,
    GlError,
    Lists,
    SceneError,
    SpatialHash,
    __version__,
    age_experiment,
    bench,
    build,
    figure_fig2,
    figure_fig8,
    figure_fig10,
    frontier,
    gl_info,
    key_experiment,
    memory_table,
    offsets,
    plan,
    read_fragments,
    sweep,
    techniques,
    voxelize,
)


class Table(dict):
    """A result table: column name -> numpy array (one entry per row).

    int64 columns have no gaps; float64 columns hold NaN where a value does
    not apply; text and histograms are object arrays. `title`, `notes` and
    `provenance` say what produced it. pandas.DataFrame(table) makes a frame.
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.title = ""
        self.notes = {}
        self.provenance = {}

    @property
    def rows(self):
        """The number of rows."""
        return len(next(iter(self.values()))) if self else 0

    def __repr__(self):
        return "Table(%r, %d rows: %s)" % (self.title, self.rows, ", ".join(self.keys()))


def HaBuffer(screen, **kwargs):
    """The HA-buffer's container: Buffer('ha', screen=screen, **kwargs)."""
    return Buffer("ha", screen=screen, **kwargs)


__all__ = [
    "FRAGMENT_DTYPE", "Buffer", "DataError", "GlError", "HaBuffer", "Lists", "SceneError", "SpatialHash",
    "Table", "age_experiment", "bench", "build", "figure_fig2", "figure_fig8", "figure_fig10", "frontier", "gl_info", "key_experiment",
    "memory_table", "offsets", "plan", "read_fragments", "sweep", "techniques", "voxelize",
]
