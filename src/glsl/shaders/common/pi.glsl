// pi, rounded to float: the constant every specula shader shares (docs/math.md 2).
const float SPECULA_PI = ${pi};
