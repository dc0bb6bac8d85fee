"""Plots of results, one module per figure family (matplotlib is imported when a figure is
drawn, here and in :mod:`dynstiff.report.robot3d` only).

Each function takes ``ax=`` (an existing Axes) and returns the matplotlib Figure; none calls
``show()``. Artists that tests and users may want to find again carry a ``gid``:

==================  ===========================================================
gid                 artist
==================  ===========================================================
``mode-global``     vertical line at a global (platform) mode, :func:`plot_frf`
``mode-local``      vertical line at a local (cable) mode, :func:`plot_frf`
``track-<id>``      frequency line of global track ``id``, :func:`plot_veering`
``local-modes``     scatter of the local modes, :func:`plot_veering`
``mode-marker``     vertical line at a given frequency, :func:`plot_spectrum`
``spectrum-<ch>``   amplitude of channel ``ch``, :func:`plot_spectrum`
``model-<name>``    point and annotation of a model, :func:`plot_speed_accuracy`
``pareto``          Pareto front (step line), :func:`plot_speed_accuracy`
``modes-<kind>``    stems of the global / local modes, :func:`plot_modes`
``damped-modes``    scatter of the damped roots, :func:`plot_damped_modes`
``cable-<family>``  stems of one family of cable modes, :func:`plot_cable_modes`
``tension-<end>``   bars of the tensions at B / A, :func:`plot_tensions`
``limit-<name>``    horizontal line at a limit, :func:`plot_tensions`,
                    :func:`plot_model_errors`
``rung-errors``     bars of the predicted errors, :func:`plot_model_errors`
==================  ===========================================================
"""

from dynstiff.plot.accuracy import plot_speed_accuracy
from dynstiff.plot.common import figure_axes, mode_categories
from dynstiff.plot.frf import plot_frf
from dynstiff.plot.modes import (
    plot_cable_modes,
    plot_damped_modes,
    plot_model_errors,
    plot_modes,
    plot_tensions,
)
from dynstiff.plot.sweep import plot_veering
from dynstiff.plot.time import plot_spectrum, plot_tracking

__all__ = ["figure_axes", "mode_categories", "plot_cable_modes", "plot_damped_modes",
           "plot_frf", "plot_model_errors", "plot_modes", "plot_spectrum", "plot_speed_accuracy",
           "plot_tensions", "plot_tracking", "plot_veering"]
