function ctsfem_json(path, s)
% Writes the struct S as a JSON object to PATH, every number with 17 significant digits.
% Fields: a char array is written as a string; a 3 x n matrix whose field name starts with
% 'nodes' as a list of [x, y, z] points; any other numeric array as a flat list (column
% order), a scalar as a number.
  fid = fopen(path, 'w');
  names = fieldnames(s);
  fprintf(fid, '{\n');
  for i = 1:numel(names)
    v = s.(names{i});
    fprintf(fid, '  "%s": ', names{i});
    if ischar(v)
      fprintf(fid, '"%s"', v);
    elseif strncmp(names{i}, 'nodes', 5)
      fprintf(fid, '[');
      for j = 1:size(v, 2)
        if j > 1, fprintf(fid, ', '); end
        fprintf(fid, '[%s]', numlist(v(:, j)));
      end
      fprintf(fid, ']');
    elseif isscalar(v)
      fprintf(fid, '%s', num(v));
    else
      fprintf(fid, '[%s]', numlist(v(:)));
    end
    if i < numel(names), fprintf(fid, ','); end
    fprintf(fid, '\n');
  end
  fprintf(fid, '}\n');
  fclose(fid);
end

function t = num(x)
  if x == round(x) && abs(x) < 1e15
    t = sprintf('%.1f', x);
  else
    t = sprintf('%.17g', x);
  end
end

function t = numlist(v)
  parts = arrayfun(@num, v, 'UniformOutput', false);
  t = strjoin(parts, ', ');
end
