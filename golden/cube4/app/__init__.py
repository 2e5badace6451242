"""The application above the specification: files, images, the cluster, the command line.

The specification (every other module of ``cube4``: the bit-exact model, the float64
reference, the host's tables and plans, the view, the scenes, the built-in phantoms)
imports only NumPy and the standard library. This package holds what a user's run adds
around it, and the libraries that brings:

* ``volumes``, ``volume_files``, ``dicom``, ``orient``: volume files (raw, NRRD, NIfTI,
  DICOM series; nibabel, pynrrd, pydicom) and ``load_volume``;
* ``warp``: the base plane resampled into the image plane (OpenImageIO);
* ``render``: the engines, a view's image, bricked views;
* ``images``, ``outputs``: image files (OpenImageIO), all-or-nothing outputs;
* ``cluster``: bricks on a Dask cluster;
* ``progress``: progress bars (tqdm) for the specification's progress callbacks;
* ``cli``: the ``cube4`` command line.

Nothing in the specification imports this package (tests/test_layers.py).
"""
