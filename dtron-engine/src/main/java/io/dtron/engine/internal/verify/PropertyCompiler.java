package io.dtron.engine.internal.verify;

import io.dtron.engine.verify.QueryException;
import io.dtron.model.ChannelVariable;
import io.dtron.model.ClockVariable;
import io.dtron.model.Location;
import io.dtron.model.NearestNames;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.Type;
import io.dtron.model.Variable;
import io.dtron.xta.Diagnostic;
import io.dtron.xta.Fragment;
import io.dtron.xta.ModelSyntax;
import io.dtron.xta.Parsed;
import io.dtron.xta.ast.Decl;
import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.Initializer;
import io.dtron.xta.ast.Nta;
import io.dtron.xta.ast.TypeExpr;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.stream.Stream;

/**
 * Compiles the state properties of queries over one network: locations ({@code P.loc}, {@code Train(1).Cross}),
 * integer variables and arrays, the model's global constants and integer typedefs, clock constraints ({@code x
 * <= 5}, {@code x - y < 3}), {@code deadlock}, the boolean operators, and {@code forall}/{@code exists} over
 * integer ranges (expanded when compiled).
 */
public final class PropertyCompiler {
    private final Network network;
    private final Map<String, Integer> constants = new HashMap<>();
    private final Map<String, int[]> ranges = new HashMap<>();
    private final Map<String, Integer> bound = new HashMap<>();
    /** Ticks per model time unit of the zones the properties are applied to: clock constants are scaled by it. */
    private final int scale;
    private String query;
    private int column;

    /** A compiler for properties of {@code network}. */
    public PropertyCompiler(Network network) {
        this(network, 1);
    }

    /** A compiler for properties of {@code network} applied to zones of {@code scale} ticks per time unit. */
    PropertyCompiler(Network network, int scale) {
        this.network = network;
        this.scale = scale;
        readGlobalConstants();
    }

    /**
     * Compiles a property written in {@code query} from 1-based {@code column}, or its negation.
     *
     * @throws QueryException for syntax errors, unknown names and what queries cannot say
     */
    Property compile(String queryText, String property, int startColumn, boolean negated) {
        this.query = queryText;
        this.column = startColumn;
        Parsed<Expr> parsed = ModelSyntax.parseExpression("query", property);
        for (Diagnostic d : parsed.diagnostics()) {
            if (d.isError()) {
                int at = d.pos() == null ? 0 : d.pos().start();
                String implication = QueryParser.implicationMistake(property, at, false);
                throw error(at, implication != null ? implication : d.message());
            }
        }
        bound.clear();
        return bool(parsed.value(), negated);
    }

    private QueryException error(Expr at, String message) {
        return error(at.pos().start(), message);
    }

    private QueryException error(int offset, String message) {
        return new QueryException("query '" + query + "', column " + (column + offset) + ": " + message);
    }

    // ---------------------------------------------------------------- boolean formulas (negation normal form)

    private Property bool(Expr e, boolean negated) {
        if (e instanceof Expr.BoolLit b) {
            return new Property.Constant(b.value() != negated);
        }
        if (e instanceof Expr.Deadlock) {
            return new Property.Deadlock(negated);
        }
        if (e instanceof Expr.Unary u && u.op() == Expr.UnaryOp.NOT) {
            return bool(u.operand(), !negated);
        }
        if (e instanceof Expr.Binary b) {
            switch (b.op()) {
                case AND, OR -> {
                    boolean conj = (b.op() == Expr.BinaryOp.AND) != negated;
                    List<Property> parts = List.of(bool(b.left(), negated), bool(b.right(), negated));
                    return conj ? new Property.And(parts) : new Property.Or(parts);
                }
                case IMPLY -> {
                    List<Property> parts = List.of(bool(b.left(), !negated), bool(b.right(), negated));
                    return negated ? new Property.And(parts) : new Property.Or(parts);
                }
                default -> {
                    if (b.op().isComparison() && (isClock(b.left()) || isClock(b.right()))) {
                        return clockComparison(b, negated);
                    }
                }
            }
        }
        if (e instanceof Expr.Quantifier q && q.kind() != Expr.QuantifierKind.SUM) {
            int[] range = range(q.type(), q);
            List<Property> parts = new ArrayList<>();
            Integer outer = bound.get(q.name());
            for (int v = range[0]; v <= range[1]; v++) {
                bound.put(q.name(), v);
                parts.add(bool(q.body(), negated));
            }
            restore(q.name(), outer);
            boolean conj = (q.kind() == Expr.QuantifierKind.FORALL) != negated;
            return conj ? new Property.And(parts) : new Property.Or(parts);
        }
        Optional<Property> location = location(e, negated);
        if (location.isPresent()) {
            return location.get();
        }
        return new Property.Data(integer(e), negated);
    }

    private void restore(String name, Integer outer) {
        if (outer == null) {
            bound.remove(name);
        } else {
            bound.put(name, outer);
        }
    }

    /** {@code P.loc}: a process's location. */
    private Optional<Property> location(Expr e, boolean negated) {
        if (!(e instanceof Expr.Field f)) {
            return Optional.empty();
        }
        Process p = process(f.value());
        if (p == null) {
            return Optional.empty();
        }
        Location l = p.location(f.name());
        if (l == null) {
            return Optional.empty();
        }
        return Optional.of(new Property.AtLocation(p.index(), l.index(), negated));
    }

    /** The process an expression names ({@code Gate}, {@code Train(1)}), or null. */
    private Process process(Expr e) {
        String name = processName(e);
        return name == null ? null : network.process(name).orElse(null);
    }

    /** The name of the process an expression would name ({@code Gate}, {@code Train(1)}), or null. */
    private String processName(Expr e) {
        if (e instanceof Expr.Ident id && !bound.containsKey(id.name())) {
            return id.name();
        }
        if (e instanceof Expr.Call c && c.function() instanceof Expr.Ident f) {
            StringBuilder sb = new StringBuilder(f.name()).append('(');
            for (int i = 0; i < c.args().size(); i++) {
                sb.append(i == 0 ? "" : ",").append(constant(c.args().get(i)));
            }
            return sb.append(')').toString();
        }
        return null;
    }

    // ---------------------------------------------------------------- clock constraints

    /** {@code x_i - x_j + offset}: a clock term (j is 0 for a single clock). */
    private record ClockTerm(int i, int j, Property.IntTerm offset) {
    }

    private boolean isClock(Expr e) {
        if (e instanceof Expr.Binary b && (b.op() == Expr.BinaryOp.ADD || b.op() == Expr.BinaryOp.SUB)) {
            return isClock(b.left()) || isClock(b.right());
        }
        return clock(e) >= 0;
    }

    private Property clockComparison(Expr.Binary b, boolean negated) {
        ClockTerm left = clockTerm(b.left());
        ClockTerm right = clockTerm(b.right());
        // left.i - left.j + left.off  op  right.i - right.j + right.off
        int i;
        int j;
        Property.IntTerm lo = left.offset;
        Property.IntTerm ro = right.offset;
        if (left.i > 0 && right.i > 0) {
            if (left.j > 0 || right.j > 0) {
                throw error(b, "a clock constraint compares at most two clocks");
            }
            i = left.i;
            j = right.i;
        } else if (left.i > 0) {
            i = left.i;
            j = left.j;
        } else if (right.i > 0) {
            // c op x - y  is  y - x op' -c: swap sides and flip the operator
            Expr.BinaryOp flipped = switch (b.op()) {
                case LT -> Expr.BinaryOp.GT;
                case LE -> Expr.BinaryOp.GE;
                case GT -> Expr.BinaryOp.LT;
                case GE -> Expr.BinaryOp.LE;
                default -> b.op();
            };
            return clockComparison(new Expr.Binary(b.pos(), flipped, b.right(), b.left()), negated);
        } else {
            throw error(b, "not a clock constraint");
        }
        // x_i - x_j  op  c  with c = ro - lo
        int k = scale;
        Property.IntTerm c = s -> k * (ro.eval(s) - lo.eval(s));
        Property.IntTerm minusC = s -> k * (lo.eval(s) - ro.eval(s));
        Property.ClockBound upperStrict = new Property.ClockBound(i, j, c, true);
        Property.ClockBound upper = new Property.ClockBound(i, j, c, false);
        Property.ClockBound lowerStrict = new Property.ClockBound(j, i, minusC, true);
        Property.ClockBound lower = new Property.ClockBound(j, i, minusC, false);
        Property p = switch (b.op()) {
            case LT -> negated ? upperStrict.negate() : upperStrict;
            case LE -> negated ? upper.negate() : upper;
            case GT -> negated ? lowerStrict.negate() : lowerStrict;
            case GE -> negated ? lower.negate() : lower;
            case EQ -> negated ? new Property.Or(List.of(upper.negate(), lower.negate()))
                    : new Property.And(List.of(upper, lower));
            case NE -> negated ? new Property.And(List.of(upper, lower))
                    : new Property.Or(List.of(upper.negate(), lower.negate()));
            default -> throw error(b, "'" + b.op().symbol() + "' does not compare clocks");
        };
        return p;
    }

    private ClockTerm clockTerm(Expr e) {
        int x = clock(e);
        if (x >= 0) {
            return new ClockTerm(x, 0, s -> 0);
        }
        if (e instanceof Expr.Binary b && (b.op() == Expr.BinaryOp.ADD || b.op() == Expr.BinaryOp.SUB)
                && isClock(b.left())) {
            ClockTerm left = clockTerm(b.left());
            if (b.op() == Expr.BinaryOp.SUB && isClock(b.right())) {
                ClockTerm right = clockTerm(b.right());
                if (left.j > 0 || right.j > 0) {
                    throw error(e, "a clock constraint compares at most two clocks");
                }
                Property.IntTerm lo = left.offset;
                Property.IntTerm ro = right.offset;
                return new ClockTerm(left.i, right.i, s -> lo.eval(s) - ro.eval(s));
            }
            Property.IntTerm off = integer(b.right());
            Property.IntTerm lo = left.offset;
            return new ClockTerm(left.i, left.j, b.op() == Expr.BinaryOp.ADD ? s -> lo.eval(s) + off.eval(s)
                    : s -> lo.eval(s) - off.eval(s));
        }
        if (e instanceof Expr.Binary b && b.op() == Expr.BinaryOp.ADD && isClock(b.right())) {
            return clockTerm(new Expr.Binary(b.pos(), b.op(), b.right(), b.left()));
        }
        if (isClock(e)) {
            throw error(e, "clocks may only be added to or subtracted from integers");
        }
        return new ClockTerm(0, 0, integer(e));
    }

    /** The clock index (1..) an expression names, or -1. */
    private int clock(Expr e) {
        if (e instanceof Expr.Ident id && !bound.containsKey(id.name()) && !constants.containsKey(id.name())) {
            return network.clock(id.name()).filter(c -> c.type() instanceof Type.Clock).map(ClockVariable::index)
                    .orElse(-1);
        }
        if (e instanceof Expr.Field f) {
            Process p = process(f.value());
            if (p != null) {
                return network.clock(p.name() + "." + f.name()).filter(c -> c.type() instanceof Type.Clock)
                        .map(ClockVariable::index).orElse(-1);
            }
        }
        if (e instanceof Expr.Index ix) {
            ClockVariable array = clockArray(ix.array());
            if (array != null) {
                Type.Array t = (Type.Array) array.type();
                int i = constant(ix.index()) - t.firstIndex();
                if (i < 0 || i >= t.length()) {
                    throw error(ix.index(), "index " + (i + t.firstIndex()) + " is out of the range of " + array.name());
                }
                return array.index() + i * t.element().clocks();
            }
        }
        return -1;
    }

    private ClockVariable clockArray(Expr e) {
        String name = e instanceof Expr.Ident id ? id.name()
                : e instanceof Expr.Field f && process(f.value()) != null ? process(f.value()).name() + "." + f.name()
                : null;
        return name == null ? null : network.clock(name).filter(c -> c.type() instanceof Type.Array).orElse(null);
    }

    // ---------------------------------------------------------------- integer expressions

    private Property.IntTerm integer(Expr e) {
        if (e instanceof Expr.IntLit l) {
            int v = (int) l.value();
            return s -> v;
        }
        if (e instanceof Expr.BoolLit b) {
            int v = b.value() ? 1 : 0;
            return s -> v;
        }
        if (e instanceof Expr.Ident id) {
            if (bound.containsKey(id.name())) {
                int v = bound.get(id.name());
                return s -> v;
            }
            if (constants.containsKey(id.name())) {
                int v = constants.get(id.name());
                return s -> v;
            }
        }
        if (e instanceof Expr.Unary u) {
            Property.IntTerm a = integer(u.operand());
            return switch (u.op()) {
                case NEG -> s -> -a.eval(s);
                case PLUS -> a;
                case NOT -> s -> a.eval(s) == 0 ? 1 : 0;
                default -> throw error(e, "'" + u.op().symbol() + "' changes the state: not allowed in a query");
            };
        }
        if (e instanceof Expr.Binary b) {
            if (isClock(b.left()) || isClock(b.right())) {
                throw error(e, "a clock constraint cannot be used as a number");
            }
            if (b.op() == Expr.BinaryOp.EQ || b.op() == Expr.BinaryOp.NE) {
                QueryException notAValue = processAsValue(b.left(), b.right());
                notAValue = notAValue != null ? notAValue : processAsValue(b.right(), b.left());
                if (notAValue != null) {
                    throw notAValue;
                }
            }
            Property.IntTerm l = integer(b.left());
            Property.IntTerm r = integer(b.right());
            return switch (b.op()) {
                case MUL -> s -> l.eval(s) * r.eval(s);
                case DIV -> s -> {
                    int d = r.eval(s);
                    if (d == 0) {
                        throw error(e, "division by zero");
                    }
                    return l.eval(s) / d;
                };
                case MOD -> s -> {
                    int d = r.eval(s);
                    if (d == 0) {
                        throw error(e, "division by zero");
                    }
                    return l.eval(s) % d;
                };
                case ADD -> s -> l.eval(s) + r.eval(s);
                case SUB -> s -> l.eval(s) - r.eval(s);
                case POW -> s -> power(l.eval(s), r.eval(s), e);
                case SHL -> s -> l.eval(s) << r.eval(s);
                case SHR -> s -> l.eval(s) >> r.eval(s);
                case MIN -> s -> Math.min(l.eval(s), r.eval(s));
                case MAX -> s -> Math.max(l.eval(s), r.eval(s));
                case LT -> s -> l.eval(s) < r.eval(s) ? 1 : 0;
                case LE -> s -> l.eval(s) <= r.eval(s) ? 1 : 0;
                case GE -> s -> l.eval(s) >= r.eval(s) ? 1 : 0;
                case GT -> s -> l.eval(s) > r.eval(s) ? 1 : 0;
                case EQ -> s -> l.eval(s) == r.eval(s) ? 1 : 0;
                case NE -> s -> l.eval(s) != r.eval(s) ? 1 : 0;
                case BIT_AND -> s -> l.eval(s) & r.eval(s);
                case BIT_XOR -> s -> l.eval(s) ^ r.eval(s);
                case BIT_OR -> s -> l.eval(s) | r.eval(s);
                case AND -> s -> l.eval(s) != 0 && r.eval(s) != 0 ? 1 : 0;
                case OR -> s -> l.eval(s) != 0 || r.eval(s) != 0 ? 1 : 0;
                case IMPLY -> s -> l.eval(s) == 0 || r.eval(s) != 0 ? 1 : 0;
            };
        }
        if (e instanceof Expr.Conditional c) {
            Property.IntTerm cond = integer(c.condition());
            Property.IntTerm then = integer(c.then());
            Property.IntTerm otherwise = integer(c.otherwise());
            return s -> cond.eval(s) != 0 ? then.eval(s) : otherwise.eval(s);
        }
        if (e instanceof Expr.Field f) {
            Process p = process(f.value());
            if (p != null && p.location(f.name()) != null) {
                int proc = p.index();
                int loc = p.location(f.name()).index();
                return s -> s.location(proc) == loc ? 1 : 0;
            }
        }
        if (e instanceof Expr.Quantifier q && q.kind() == Expr.QuantifierKind.SUM) {
            int[] range = range(q.type(), q);
            List<Property.IntTerm> parts = new ArrayList<>();
            Integer outer = bound.get(q.name());
            for (int v = range[0]; v <= range[1]; v++) {
                bound.put(q.name(), v);
                parts.add(integer(q.body()));
            }
            restore(q.name(), outer);
            Property.IntTerm[] terms = parts.toArray(new Property.IntTerm[0]);
            return s -> {
                int sum = 0;
                for (Property.IntTerm t : terms) {
                    sum += t.eval(s);
                }
                return sum;
            };
        }
        if (e instanceof Expr.Quantifier || e instanceof Expr.Deadlock) {
            throw error(e, "a formula cannot be used as a number here");
        }
        return variable(e);
    }

    /** A slot of the state vector: a variable, an array element, a process's local variable. */
    private Property.IntTerm variable(Expr e) {
        if (e instanceof Expr.Index ix) {
            Variable array = arrayVariable(ix.array());
            if (array == null) {
                throw error(ix.array(), "'" + ix.array().pos().text() + "' is not an integer array of the model");
            }
            Type.Array t = (Type.Array) array.type();
            if (t.element().slots() != 1) {
                throw error(e, "only arrays of integers can be indexed in a query");
            }
            Property.IntTerm index = integer(ix.index());
            int first = t.firstIndex();
            int length = t.length();
            int offset = array.offset();
            String name = array.name();
            return s -> {
                int i = index.eval(s) - first;
                if (i < 0 || i >= length) {
                    throw error(ix.index(), "index " + (i + first) + " is out of the range of " + name);
                }
                return s.var(offset + i);
            };
        }
        String name = variableName(e);
        if (name == null) {
            QueryException notAValue = processAsValue(e, null);
            if (notAValue != null) {
                throw notAValue;
            }
            if (e instanceof Expr.Field f) {
                throw unknownProcess(f);
            }
            throw error(e, "'" + e.pos().text() + "' cannot be used in a query");
        }
        Optional<Variable> v = network.variable(name);
        if (v.isEmpty()) {
            if (network.clock(name).isPresent()) {
                throw error(e, "the clock '" + name + "' can only be compared, not used as a number");
            }
            if (network.channel(name).map(ChannelVariable::name).isPresent()) {
                throw error(e, "the channel '" + name + "' cannot be used in a query");
            }
            if (e instanceof Expr.Field f && process(f.value()) != null) {
                throw noMember(process(f.value()), f);
            }
            QueryException notAValue = processAsValue(e, null);
            if (notAValue != null) {
                throw notAValue;
            }
            List<String> names = new ArrayList<>(bound.keySet());
            names.addAll(constants.keySet());
            network.variables().stream().filter(g -> g.owner() == null).forEach(g -> names.add(g.name()));
            network.clocks().stream().filter(g -> g.owner() == null).forEach(g -> names.add(g.name()));
            String hint = NearestNames.hint(name, names);
            if (hint.isEmpty()) {
                // a process's own variable or clock, named without its process
                List<String> local = Stream.concat(network.variables().stream().map(Variable::name),
                                network.clocks().stream().map(ClockVariable::name))
                        .filter(n -> n.endsWith("." + name)).limit(NearestNames.MAX).toList();
                hint = NearestNames.didYouMean(local);
            }
            throw error(e, "unknown name '" + name + "'" + hint);
        }
        if (v.get().type().slots() != 1 || !v.get().type().isIntegral()) {
            throw error(e, "'" + name + "' is not an integer, boolean or scalar");
        }
        int slot = v.get().offset();
        return s -> s.var(slot);
    }

    private Variable arrayVariable(Expr e) {
        String name = variableName(e);
        return name == null ? null : network.variable(name).filter(v -> v.type() instanceof Type.Array).orElse(null);
    }

    private String variableName(Expr e) {
        if (e instanceof Expr.Ident id) {
            return id.name();
        }
        if (e instanceof Expr.Field f) {
            Process p = process(f.value());
            return p == null ? null : p.name() + "." + f.name();
        }
        return null;
    }

    // ---------------------------------------------------------------- names that are not what the query needs

    /**
     * The error for a process or template used as a value ({@code Train == Cross}, {@code x + Gate}), saying how
     * to test a location instead, or null when {@code e} names neither. {@code other}, when it names a location of
     * the process ({@code Cross}), is the location the example tests.
     */
    private QueryException processAsValue(Expr e, Expr other) {
        String name = e instanceof Expr.Ident
                || e instanceof Expr.Call c && c.function() instanceof Expr.Ident f && isTemplate(f.name())
                ? processName(e) : null;
        if (name == null) {
            return null;
        }
        Optional<Process> p = network.process(name);
        if (p.isPresent()) {
            String location = other instanceof Expr.Ident id && p.get().location(id.name()) != null ? id.name()
                    : exampleLocation(p.get());
            return error(e, "'" + name + "' is a process, not a value: " + name + "." + location + " tests whether it"
                    + " is in location " + location);
        }
        Optional<Process> instance = instanceOf(name);
        if (instance.isPresent()) {
            String example = instance.get().name() + "." + exampleLocation(instance.get());
            return error(e, "'" + name + "' is a template, not a value: a query tests the location of one of its"
                    + " processes, as " + example);
        }
        return null;
    }

    /** The error for {@code P.name} where {@code P} is no process: a template, or an unknown process. */
    private QueryException unknownProcess(Expr.Field f) {
        String name = processName(f.value());
        if (name == null || f.value() instanceof Expr.Ident id
                && (constants.containsKey(id.name()) || network.variable(id.name()).isPresent()
                || network.clock(id.name()).isPresent() || network.channel(id.name()).isPresent())) {
            return error(f, "'" + f.pos().text() + "' cannot be used in a query");
        }
        Optional<Process> instance = instanceOf(name);
        if (instance.isPresent()) {
            return error(f.value(), "'" + name + "' is a template, not a process: name one of its processes, as "
                    + instance.get().name() + "." + f.name());
        }
        if (f.value() instanceof Expr.Call c && c.function() instanceof Expr.Ident template
                && isTemplate(template.name())) {
            List<String> processes = network.processes().stream().filter(p -> p.template().equals(template.name()))
                    .map(Process::name).toList();
            String list = processes.size() <= 4 ? String.join(", ", processes)
                    : String.join(", ", processes.subList(0, 3)) + ", ..., " + processes.get(processes.size() - 1);
            return error(f.value(), "unknown process '" + name + "': the processes of template " + template.name()
                    + " are " + list);
        }
        List<String> names = new ArrayList<>(network.templates());
        network.processes().forEach(p -> names.add(p.name()));
        return error(f.value(), "unknown process '" + name + "'" + NearestNames.hint(name, names));
    }

    /** The error for {@code P.name} where process {@code P} has no location, variable or clock {@code name}. */
    private QueryException noMember(Process p, Expr.Field f) {
        Map<String, String> members = new HashMap<>();
        String prefix = p.name() + ".";
        network.clocks().stream().filter(c -> p.name().equals(c.owner()))
                .forEach(c -> members.put(c.name().substring(prefix.length()), "clock"));
        network.variables().stream().filter(v -> p.name().equals(v.owner()))
                .forEach(v -> members.put(v.name().substring(prefix.length()), "variable"));
        p.locations().forEach(l -> members.put(l.name(), "location"));
        List<String> near = NearestNames.of(f.name(), members.keySet());
        String kinds = near.isEmpty() ? "location or variable"
                : String.join(" or ", near.stream().map(members::get).distinct().sorted().toList());
        return error(f.pos().end() - f.name().length(), "process " + p.name() + " has no " + kinds + " '" + f.name()
                + "'" + NearestNames.hint(f.name(), members.keySet()));
    }

    private boolean isTemplate(String name) {
        return network.processes().stream().anyMatch(p -> p.template().equals(name));
    }

    /** The first process of template {@code name} when no process has that name, else empty. */
    private Optional<Process> instanceOf(String name) {
        return network.process(name).isPresent() ? Optional.empty()
                : network.processes().stream().filter(p -> p.template().equals(name)).findFirst();
    }

    /** A location to show in an example: the initial one, unless Uppaal named it ({@code _id3}) and another has a name. */
    private static String exampleLocation(Process p) {
        String initial = p.locations().get(p.initial()).name();
        return !initial.startsWith("_") ? initial : p.locations().stream().map(Location::name)
                .filter(n -> !n.startsWith("_")).findFirst().orElse(initial);
    }

    // ---------------------------------------------------------------- constants and ranges

    private int constant(Expr e) {
        try {
            return integer(e).eval(null);
        } catch (NullPointerException notConstant) {
            throw error(e, "'" + e.pos().text() + "' is not a constant");
        }
    }

    private int[] range(TypeExpr type, Expr at) {
        if (type instanceof TypeExpr.IntType t && t.lower() != null && t.upper() != null) {
            return new int[] {constant(t.lower()), constant(t.upper())};
        }
        if (type instanceof TypeExpr.NamedType n && ranges.containsKey(n.name())) {
            return ranges.get(n.name());
        }
        throw error(at, "a quantifier ranges over an integer range int[a,b] or a typedef of one");
    }

    /**
     * Reads the global constants and integer typedefs from the model's global declarations, so that queries can
     * use them as the model does ({@code N}, {@code id_t}).
     */
    private void readGlobalConstants() {
        Fragment declarations = Stream.of(
                        network.variables().stream().filter(v -> v.owner() == null).map(v -> v.pos()),
                        network.clocks().stream().filter(c -> c.owner() == null).map(c -> c.pos()),
                        network.channels().stream().filter(c -> c.owner() == null).map(c -> c.pos()))
                .flatMap(s -> s).filter(p -> p != null && p.fragment().template() == null)
                .map(p -> p.fragment()).findFirst().orElse(null);
        if (declarations == null) {
            return;
        }
        Parsed<Nta> parsed = ModelSyntax.parseXta(declarations.file(), declarations.text());
        if (parsed.value() == null) {
            return;
        }
        this.query = "";
        for (Decl d : parsed.value().declarations()) {
            try {
                if (d instanceof Decl.Variable v && v.dims().isEmpty()
                        && v.type() instanceof TypeExpr.IntType t && t.qualifiers().contains(TypeExpr.Qualifier.CONST)
                        && v.init() instanceof Initializer.Single init) {
                    constants.put(v.name(), constant(init.value()));
                } else if (d instanceof Decl.Variable v && v.dims().isEmpty() && v.init() instanceof Initializer.Single init
                        && v.type() instanceof TypeExpr.PrimitiveType t && t.primitive() == TypeExpr.Primitive.BOOL
                        && t.qualifiers().contains(TypeExpr.Qualifier.CONST)) {
                    constants.put(v.name(), constant(init.value()));
                } else if (d instanceof Decl.Typedef t && t.dims().isEmpty() && t.type() instanceof TypeExpr.IntType i
                        && i.lower() != null && i.upper() != null) {
                    ranges.put(t.name(), new int[] {constant(i.lower()), constant(i.upper())});
                }
            } catch (QueryException notConstant) {
                // a declaration whose value the query compiler cannot compute is not available to queries
            }
        }
    }

    /** {@code base ** exponent} as the engine computes it: a negative exponent or an overflow is an error. */
    private int power(int base, int exponent, Expr at) {
        if (exponent < 0) {
            throw error(at, "negative exponent");
        }
        if (base == 0 || base == 1) {
            return exponent == 0 ? 1 : base;
        }
        if (base == -1) {
            return exponent % 2 == 0 ? 1 : -1;
        }
        long value = 1;
        for (int i = 0; i < exponent; i++) {
            value *= base; // |base| >= 2: an overflow comes within 32 steps
            if ((int) value != value) {
                throw error(at, "overflow");
            }
        }
        return (int) value;
    }
}
