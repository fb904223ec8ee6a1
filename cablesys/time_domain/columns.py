"""A CasADi function evaluated over many columns, numpy arrays in and out.

Calling a ``casadi.Function`` with numpy arrays converts them to and from ``DM`` number by
number (for the outputs of a segmented cable over a run, several times the cost of evaluating them), and a call with several columns builds a new
``map`` every time. :class:`Columns` maps the function once over a fixed block of columns and
evaluates it through CasADi's ``FunctionBuffer`` on numpy memory: no conversion, no rebuild.
"""

from __future__ import annotations

import threading

import casadi as ca
import numpy as np

from ..errors import ParameterError


def _flat(a: np.ndarray) -> memoryview:
    """A 1-D view of a Fortran-ordered array (what ``FunctionBuffer`` accepts)."""
    return memoryview(a.ravel(order="K"))


class Columns:
    """``f`` evaluated column by column on numpy arrays.

    Parameters
    ----------
    f : casadi.Function
        A function whose inputs are dense column vectors and outputs column vectors (structural
        zeros are returned as zeros).
    block : int, optional
        Columns per evaluation of the mapped function (a run of n columns takes
        ceil(n / block) evaluations; the last block is padded with copies of the last column).
    """

    def __init__(self, f: ca.Function, block: int = 256):
        for i in range(f.n_in()):
            if not (f.sparsity_in(i).is_dense() and f.size2_in(i) == 1):
                raise ParameterError(f"{f.name()}.input[{i}]", f.sparsity_in(i).dim(), "must be a dense column vector")
        for i in range(f.n_out()):
            if f.size2_out(i) != 1:
                raise ParameterError(f"{f.name()}.output[{i}]", f.sparsity_out(i).dim(), "must be a column vector")
        self._rows = [np.asarray(f.sparsity_out(i).row(), dtype=int) for i in range(f.n_out())]
        self.f, self.block = f, int(block)
        self._lock = threading.Lock()           # one set of buffers: one evaluation at a time
        self._mapped = f.map(self.block)
        self._buf, self._eval = self._mapped.buffer()
        self._in = [np.zeros((f.nnz_in(i), self.block), order="F") for i in range(f.n_in())]
        self._out = [np.zeros((f.nnz_out(i), self.block), order="F") for i in range(f.n_out())]
        for i, a in enumerate(self._in):
            self._buf.set_arg(i, _flat(a))
        for i, a in enumerate(self._out):
            self._buf.set_res(i, _flat(a))

    def __call__(self, *args) -> list[np.ndarray]:
        """Outputs of ``f`` at every column of ``args``.

        Parameters
        ----------
        *args : array_like
            One per input of ``f``: shape (rows,) or (rows, 1), the same for every column,
            or (rows, n), one column per evaluation (n the same for all such inputs).

        Returns
        -------
        list of numpy.ndarray
            One (rows_out, n) array per output of ``f``.

        Raises
        ------
        RuntimeError
            When ``f`` reports a failed evaluation.
        """
        if len(args) != self.f.n_in():
            raise ParameterError("args", len(args), f"must be {self.f.n_in()} arrays (the inputs of {self.f.name()})")
        args = [np.asarray(a, dtype=float).reshape(self.f.nnz_in(i), -1) for i, a in enumerate(args)]
        n = max(a.shape[1] for a in args)
        for i, a in enumerate(args):
            if a.shape[1] not in (1, n):
                raise ParameterError(f"args[{i}]", a.shape, f"must have 1 or {n} columns")
        outs = [np.zeros((self.f.size1_out(i), n)) for i in range(self.f.n_out())]
        with self._lock:
            self._blocks(args, outs, n)
        return outs

    def _blocks(self, args, outs, n) -> None:
        for j0 in range(0, n, self.block):
            m = min(self.block, n - j0)
            for a, buf in zip(args, self._in):
                if a.shape[1] == 1:
                    buf[:, :] = a
                else:
                    buf[:, :m] = a[:, j0:j0 + m]
                    buf[:, m:] = a[:, j0 + m - 1:j0 + m]       # padding: a column that evaluates
            self._eval()
            if self._buf.ret() != 0:
                raise RuntimeError(f"{self.f.name()} failed to evaluate (status {self._buf.ret()})")
            for o, rows, res in zip(outs, self._rows, self._out):
                o[rows, j0:j0 + m] = res[:, :m]
