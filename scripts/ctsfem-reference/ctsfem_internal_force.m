function fa = ctsfem_internal_force(xa, data)
% The unbalanced internal force on the free coordinates xa in CTSFEM's model, as its
% static_solver_CTS forms it: segment lengths l, clustered lengths S l, strains against the
% rest lengths data.l0, CTSFEM's stress_strain for the forces, and Ia' kron(C' diag(t./l) C, I3) n.
  global l_int f_int
  n = data.Ia * xa + data.Ib * data.xb;
  l = sqrt(sum((reshape(n, 3, []) * data.C').^2))';
  strain = (data.S * l - data.l0) ./ data.l0;
  [E, sigma] = stress_strain(data.consti_data, data.index_b, data.index_s, strain, data.material);
  t = data.S' * (sigma .* data.A);
  fa = data.Ia' * kron(data.C' * diag(t ./ l) * data.C, eye(3)) * n;
end
