function out = polish_static(data, out_s)
% CTSFEM's solver once more (the polishing copy: no line search, tolerance 1e-9 N) from its
% own result, at the last substep's rest lengths, loads and support motions.
  d = data;
  d.N = out_s.N; d.substep = 1;
  d.w_t = data.w_t(:, end); d.dnb_t = data.dnb_t(:, end); d.l0_t = data.l0_t(:, end);
  out = static_solver_CTS_polish(d);
end
