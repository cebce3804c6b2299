package io.dtron.model.internal;

import io.dtron.model.ChannelVariable;
import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.Location;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.Type;
import io.dtron.model.Variable;
import io.dtron.xta.Diagnostic;
import io.dtron.xta.Parsed;
import io.dtron.xta.Pos;
import io.dtron.xta.ast.Decl;
import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.Nta;
import io.dtron.xta.ast.Param;
import io.dtron.xta.ast.SystemLine;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.HashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;

/**
 * Turns a parsed model into a {@link Network}: declares the globals, expands the system line into processes
 * (one per value of each free parameter), binds template parameters by Uppaal's rules and compiles every
 * process's locations and edges. Templates that the system line does not use are checked too.
 */
public final class NetworkCompiler {
    private final Nta nta;
    private final Compilation compilation = new Compilation();
    private final Diagnostics diagnostics = compilation.diagnostics;
    private final DeclarationCompiler declarations = new DeclarationCompiler(compilation);
    private final Scope global = new Scope(Builtins.scope());
    private final List<Process> processes = new ArrayList<>();
    private final Set<String> instantiatedTemplates = new HashSet<>();
    private Pos firstCsp;
    private Pos firstIo;

    private NetworkCompiler(Nta nta) {
        this.nta = nta;
    }

    /** Compiles a parsed model; the value is null when there are errors. */
    public static Parsed<Network> compile(Nta nta) {
        return new NetworkCompiler(nta).run();
    }

    private Parsed<Network> run() {
        Checker checker = new Checker(compilation, global, new Frame(0));
        List<Decl> others = new ArrayList<>();
        declarations.declare(nta.declarations(), checker, null, others);
        int[] channelPriority = null;
        SystemLine system = nta.system();
        if (system == null) {
            diagnostics.add(Diagnostic.fileError(nta.file(), "the model has no system line (system P, Q;)"));
        } else {
            expandSystem(system);
        }
        for (Decl d : others) {
            if (d instanceof Decl.Template t && !instantiatedTemplates.contains(t.name())) {
                checkUninstantiated(t);
            }
        }
        for (Decl d : others) {
            if (d instanceof Decl.ChanPriority p) {
                channelPriority = channelPriorities(p, checker);
            }
        }
        if (firstCsp != null && firstIo != null) {
            diagnostics.error(firstCsp, "CSP synchronisations (sync a;) and send/receive synchronisations (a!, a?)"
                    + " cannot be mixed in one model");
        }
        List<Diagnostic> all = diagnostics.all();
        if (diagnostics.hasErrors()) {
            return new Parsed<>(null, all);
        }
        List<Integer> priorities = new ArrayList<>();
        for (int i = 0; i < compilation.channelCount(); i++) {
            priorities.add(channelPriority == null ? 0 : channelPriority[i]);
        }
        List<Diagnostic> warnings = all.stream().filter(d -> !d.isError()).sorted(Diagnostic.BY_POSITION).toList();
        Network network = new Network(nta.file(), processes, compilation.variables, compilation.clocks,
                compilation.channels, compilation.functions(), compilation.stateSize(), compilation.clockCount(),
                compilation.channelCount(), priorities, nta.queries(), warnings, compilation.startErrors);
        return new Parsed<>(network, all);
    }

    // ================================================================ the system line

    private void expandSystem(SystemLine system) {
        Set<String> listed = new HashSet<>();
        for (int level = 0; level < system.levels().size(); level++) {
            for (SystemLine.Name name : system.levels().get(level)) {
                if (!listed.add(name.name())) {
                    diagnostics.error(name.pos(), "'" + name.name() + "' is listed twice in the system line");
                    continue;
                }
                Symbol sym = global.lookup(name.name());
                List<Param> free;
                if (sym instanceof Symbol.Template t) {
                    free = t.decl().params();
                } else if (sym instanceof Symbol.Instantiation i) {
                    free = i.decl().params();
                } else {
                    diagnostics.error(name.pos(), sym == null ? "'" + name.name() + "' in the system line is not declared"
                            : "'" + name.name() + "' in the system line is not a template or an instantiation");
                    continue;
                }
                expand(name, sym, free, level);
            }
        }
    }

    /** One process per combination of values of the free parameters. */
    private void expand(SystemLine.Name name, Symbol sym, List<Param> free, int level) {
        Scope paramTypes = new Scope(global);
        Checker checker = new Checker(compilation, paramTypes, new Frame(0));
        List<int[]> ranges = new ArrayList<>();
        List<Type> types = new ArrayList<>();
        List<Boolean> consts = new ArrayList<>();
        for (Param p : free) {
            Checker.Resolved r = checker.resolve(p.type());
            if (r == null) {
                return;
            }
            Type t = checker.applyDims(r.type(), p.dims());
            if (t == null) {
                return;
            }
            boolean bounded = t instanceof Type.Int i && !i.equals(Type.Int.DEFAULT) || t instanceof Type.Scalar;
            if (p.reference() || !bounded) {
                diagnostics.error(p.pos(), "free parameter '" + p.name() + "' of " + name.name()
                        + " must be a bounded integer or a scalar passed by value, because the system line makes one"
                        + " process per value of it (it is " + (p.reference() ? "a reference to " : "") + t + ")");
                return;
            }
            ranges.add(t instanceof Type.Int i ? new int[] {i.lower(), i.upper()}
                    : new int[] {0, ((Type.Scalar) t).size() - 1});
            types.add(t);
            consts.add(r.constant());
        }
        int[] values = new int[free.size()];
        for (int i = 0; i < values.length; i++) {
            values[i] = ranges.get(i)[0];
        }
        while (true) {
            Scope scope = new Scope(global);
            StringBuilder processName = new StringBuilder(name.name());
            for (int i = 0; i < values.length; i++) {
                Param p = free.get(i);
                scope.put(p.name(), new Symbol.FreeParam(p.pos(), types.get(i), values[i], consts.get(i), name.name()));
                processName.append(i == 0 ? "(" : ",").append(values[i]);
            }
            if (values.length > 0) {
                processName.append(')');
            }
            if (sym instanceof Symbol.Template t) {
                compileProcess(t.decl(), scope, processName.toString(), level);
            } else {
                instantiate(((Symbol.Instantiation) sym).decl(), scope, processName.toString(), level, 0);
            }
            int k = values.length - 1;
            while (k >= 0 && values[k] == ranges.get(k)[1]) {
                values[k] = ranges.get(k)[0];
                k--;
            }
            if (k < 0) {
                return;
            }
            values[k]++;
        }
    }

    /** Binds the target's parameters from an instantiation's arguments, then compiles or follows the target. */
    private void instantiate(Decl.Instantiation inst, Scope argScope, String processName, int level, int depth) {
        if (depth > 64) {
            diagnostics.error(inst.pos(), "instantiation '" + inst.name() + "' refers to itself");
            return;
        }
        Symbol target = global.lookup(inst.template());
        List<Param> params;
        if (target instanceof Symbol.Template t) {
            params = t.decl().params();
        } else if (target instanceof Symbol.Instantiation i) {
            params = i.decl().params();
        } else {
            diagnostics.error(inst.templatePos(), target == null ? "unknown template '" + inst.template() + "'"
                    : "'" + inst.template() + "' is not a template");
            return;
        }
        if (params.size() != inst.args().size()) {
            diagnostics.error(inst.pos(), "'" + inst.template() + "' takes " + params.size() + " argument"
                    + (params.size() == 1 ? "" : "s") + ", but '" + inst.name() + "' gives " + inst.args().size());
            return;
        }
        Scope bound = bind(params, inst.args(), argScope, processName, inst.template());
        if (bound == null) {
            return;
        }
        if (target instanceof Symbol.Template t) {
            compileProcess(t.decl(), bound, processName, level);
        } else {
            instantiate(((Symbol.Instantiation) target).decl(), bound, processName, level, depth + 1);
        }
    }

    /** A scope with {@code params} bound to {@code args} (compiled in {@code argScope}), or null after errors. */
    private Scope bind(List<Param> params, List<Expr> args, Scope argScope, String processName, String target) {
        Scope bound = new Scope(global);
        Checker typeChecker = new Checker(compilation, bound, new Frame(0));
        Checker argChecker = new Checker(compilation, argScope, new Frame(0));
        boolean ok = true;
        for (int i = 0; i < params.size(); i++) {
            Param p = params.get(i);
            Expr argAst = args.get(i);
            Checker.Resolved r = typeChecker.resolve(p.type());
            Type pt = r == null ? null : typeChecker.applyDims(r.type(), p.dims());
            argChecker.usedNonConstFreeParam = false;
            Expression arg = argChecker.compile(argAst);
            if (pt == null || arg == null) {
                ok = false;
                continue;
            }
            Symbol symbol = bindOne(p, r.constant(), pt, argAst, arg, argChecker, processName, target);
            if (symbol == null) {
                ok = false;
            } else {
                bound.put(p.name(), symbol);
            }
        }
        return ok ? bound : null;
    }

    private Symbol bindOne(Param p, boolean constant, Type pt, Expr argAst, Expression arg, Checker argChecker,
                           String processName, String target) {
        String what = "the argument for parameter '" + p.name() + "' of " + target;
        if (argChecker.hasSideEffects(arg)) {
            diagnostics.error(argAst.pos(), what + " must be free of side effects");
            return null;
        }
        int[] values = argChecker.constantValues(arg);
        if (p.reference()) {
            if (constant) {
                if (values == null) {
                    diagnostics.error(argAst.pos(), what + " is a constant reference, so it must be computable at"
                            + " compile time");
                    return null;
                }
                if (!Checker.assignable(pt, arg)) {
                    diagnostics.error(argAst.pos(), what + " must be " + pt + ", not " + Checker.describe(arg.type()));
                    return null;
                }
                return new Symbol.Alias(p.pos(), arg, false, false, true);
            }
            String why = argChecker.notAssignable(argAst);
            if (!Checker.isLvalue(arg) || !constantIndices(arg) || why != null && !(pt.channels() > 0)) {
                diagnostics.error(argAst.pos(), what + " is a reference, so it must be a variable with constant"
                        + " indices" + (why == null ? "" : " (" + why + ")"));
                return null;
            }
            if (!Checker.sameReferenceType(pt, arg.type())) {
                diagnostics.error(argAst.pos(), what + " must be exactly " + pt + " (it is passed by reference), not "
                        + arg.type());
                return null;
            }
            return new Symbol.Alias(p.pos(), arg, true, false, true);
        }
        if (pt.clocks() > 0) {
            diagnostics.error(argAst.pos(), what + ": a clock parameter must be a reference (" + pt + " &" + p.name()
                    + ")");
            return null;
        }
        if (pt.channels() > 0) {
            if (pt instanceof Type.Array) {
                diagnostics.error(argAst.pos(), what + ": an array of channels must be passed by reference ("
                        + pt + " &" + p.name() + ")");
                return null;
            }
            if (!(arg.type() instanceof Type.Channel) || !Checker.isLvalue(arg) || !constantIndices(arg)) {
                diagnostics.error(argAst.pos(), what + " must be one channel with constant indices, not "
                        + Checker.describe(arg.type()));
                return null;
            }
            if (!pt.equals(arg.type())) {
                diagnostics.error(argAst.pos(), what + " must be a " + pt + ", but '" + argAst.pos().text() + "' is a "
                        + arg.type());
                return null;
            }
            return new Symbol.Alias(p.pos(), arg, false, false, false);
        }
        if (arg instanceof Expression.ModelError m) {
            String message = "process " + processName + ": " + what + " cannot be computed: " + m.message();
            if (constant) {
                return new Symbol.Alias(p.pos(), new Expression.ModelError(argAst.pos(), pt, message), false, false, false);
            }
            compilation.startErrors.add(Diagnostic.error(argAst.pos(), message));
            diagnostics.warning(argAst.pos(), message + "; the process cannot start");
            return localParameter(p, pt, DeclarationCompiler.defaults(pt), processName);
        }
        if (!constant && (values == null || argChecker.usedNonConstFreeParam)) {
            diagnostics.error(argAst.pos(), what + " is passed by value, so it must be computable at compile time"
                    + (argChecker.usedNonConstFreeParam ? " (a free parameter used here must be declared const)" : ""));
            return null;
        }
        if (!Checker.assignable(pt, arg)) {
            diagnostics.error(argAst.pos(), what + " must be " + pt + ", not " + Checker.describe(arg.type()));
            return null;
        }
        if (values == null) {
            return new Symbol.Alias(p.pos(), arg, false, false, false);
        }
        if (pt instanceof Type.Int i && (values[0] < i.lower() || values[0] > i.upper())
                && !(constant && i.equals(Type.Int.DEFAULT))) {
            diagnostics.error(argAst.pos(), what + " is " + values[0] + ", outside its range " + i);
            return null;
        }
        if (constant) {
            return new Symbol.Constant(p.pos(), pt, values);
        }
        return localParameter(p, pt, values, processName);
    }

    private Symbol localParameter(Param p, Type pt, int[] values, String processName) {
        Variable v = compilation.newVariable(DeclarationCompiler.qualified(processName, p.name()), pt, values, false,
                processName, p.pos());
        return new Symbol.Var(p.pos(), v);
    }

    private static boolean constantIndices(Expression e) {
        if (e instanceof Expression.Index i) {
            return i.index() instanceof Expression.Constant && constantIndices(i.array());
        }
        if (e instanceof Expression.FieldRef f) {
            return constantIndices(f.struct());
        }
        return true;
    }

    // ================================================================ processes

    private void compileProcess(Decl.Template t, Scope params, String name, int level) {
        instantiatedTemplates.add(t.name());
        if (processes.stream().anyMatch(p -> p.name().equals(name))) {
            diagnostics.error(t.pos(), "two processes are called '" + name + "'");
            return;
        }
        Process p = new ProcessCompiler(t, params, name).compile(processes.size(), level);
        if (p != null) {
            processes.add(p);
        }
    }

    /** Checks a template that no process instantiates, with placeholders for its parameters. */
    private void checkUninstantiated(Decl.Template t) {
        boolean before = compilation.detached;
        compilation.detached = true;
        try {
            Scope scope = new Scope(global);
            Checker checker = new Checker(compilation, scope, new Frame(0));
            for (Param p : t.params()) {
                Checker.Resolved r = checker.resolve(p.type());
                Type pt = r == null ? null : checker.applyDims(r.type(), p.dims());
                if (pt == null) {
                    return;
                }
                Expression placeholder;
                if (pt.clocks() > 0) {
                    placeholder = new Expression.ClockRef(p.pos(), pt, compilation.newClock(p.name(), pt, null, p.pos()));
                } else if (pt.channels() > 0) {
                    placeholder = new Expression.ChannelRef(p.pos(), pt,
                            compilation.newChannel(p.name(), pt, null, p.pos()));
                } else {
                    placeholder = new Expression.VariableRef(p.pos(), pt, compilation.newVariable(p.name(), pt,
                            DeclarationCompiler.defaults(pt), false, null, p.pos()));
                }
                scope.put(p.name(), new Symbol.Alias(p.pos(), placeholder, p.reference() || !r.constant(), true,
                        p.reference()));
            }
            new ProcessCompiler(t, scope, t.name()).compile(-1, 0);
        } finally {
            compilation.detached = before;
        }
    }

    private static boolean containsRate(Expression e) {
        if (e instanceof Expression.ClockRate) {
            return true;
        } else if (e instanceof Expression.Binary b) {
            return containsRate(b.left()) || containsRate(b.right());
        } else if (e instanceof Expression.Unary u) {
            return containsRate(u.operand());
        } else if (e instanceof Expression.Quantified q) {
            return containsRate(q.body());
        }
        return false;
    }

    /** Compiles one process: local declarations, locations, edges. */
    private final class ProcessCompiler {
        private final Set<Integer> branchpoints = new HashSet<>();
        private final Decl.Template template;
        private final Scope params;
        private final String name;

        ProcessCompiler(Decl.Template template, Scope params, String name) {
            this.template = template;
            this.params = params;
            this.name = name;
        }

        Process compile(int index, int level) {
            Scope local = new Scope(params);
            Checker checker = new Checker(compilation, local, new Frame(0));
            declarations.declare(template.declarations(), checker, name, null);
            Map<String, Integer> byId = new HashMap<>();
            Map<String, Pos> byName = new HashMap<>();
            List<Location> locations = new ArrayList<>();
            for (io.dtron.xta.ast.Location l : template.locations()) {
                String locationName = l.name() != null ? l.name() : "_" + l.id();
                if (l.name() != null && byName.containsKey(l.name())) {
                    diagnostics.error(l.pos(), "template " + template.name() + " has two locations called '" + l.name()
                            + "'");
                    continue;
                }
                byName.put(locationName, l.pos());
                if (byId.containsKey(l.id())) {
                    diagnostics.error(l.pos(), "template " + template.name() + " has two locations with id '" + l.id()
                            + "'");
                    continue;
                }
                byId.put(l.id(), locations.size());
                Frame frame = new Frame(0);
                Expression invariant = l.invariant() == null ? null
                        : invariant(l.invariant(), new Checker(compilation, new Scope(local), frame));
                Location.Kind kind = Location.Kind.valueOf(l.kind().name());
                locations.add(new Location(locations.size(), locationName, kind, invariant, frame.size(), l.pos()));
            }
            for (String id : template.branchpoints()) {
                if (byId.containsKey(id)) {
                    diagnostics.error(template.pos(), "template " + template.name() + " has two locations with id '"
                            + id + "'");
                    continue;
                }
                byId.put(id, locations.size());
                branchpoints.add(locations.size());
                locations.add(new Location(locations.size(), "_" + id, Location.Kind.BRANCHPOINT, null, 0,
                        template.pos()));
            }
            int initial = -1;
            if (template.init() == null) {
                if (!template.locations().isEmpty()) {
                    diagnostics.error(template.pos(), "template " + template.name() + " has no initial location");
                } else {
                    diagnostics.warning(template.pos(), "template " + template.name()
                            + " has no locations: its processes take no part in the run");
                }
            } else if (byId.containsKey(template.init())) {
                initial = byId.get(template.init());
            } else {
                diagnostics.error(template.initPos() == null ? template.pos() : template.initPos(), "the initial location '"
                        + template.init() + "' is not a location of template " + template.name());
            }
            List<Edge> edges = new ArrayList<>();
            for (io.dtron.xta.ast.Edge e : template.edges()) {
                Edge edge = edge(e, local, byId, edges.size());
                if (edge != null) {
                    edges.add(edge);
                }
            }
            return new Process(index, name, template.name(), locations, initial, edges, level);
        }

        /** An invariant; a conjunction is checked conjunct by conjunct, so that an error names the bad one. */
        private Expression invariant(Expr e, Checker checker) {
            if (e instanceof Expr.Binary b && b.op() == Expr.BinaryOp.AND) {
                Expression left = invariant(b.left(), checker);
                Expression right = invariant(b.right(), checker);
                if (left == null || right == null) {
                    return null;
                }
                boolean clocks = left.type() instanceof Type.ClockConstraint
                        || right.type() instanceof Type.ClockConstraint;
                return new Expression.Binary(b.pos(), clocks ? new Type.ClockConstraint(Type.ConstraintKind.INVARIANT)
                        : Type.Bool.INSTANCE, Expression.Operator.AND, left, right);
            }
            Expression x = checker.compile(e);
            if (x == null) {
                return null;
            }
            if (checker.hasSideEffects(x)) {
                diagnostics.error(e.pos(), "an invariant must not have side effects");
                return null;
            }
            if (x.type() instanceof Type.ClockConstraint c && c.kind() != Type.ConstraintKind.INVARIANT) {
                diagnostics.error(e.pos(), "an invariant is a conjunction of bounds on clocks (x <= c, x - y < c,"
                        + " x >= c, but not x == c or x != c) and conditions on data; '" + e.pos().text() + "' is not");
                return null;
            }
            if (!(x.type() instanceof Type.ClockConstraint) && !Checker.isInteger(x.type())) {
                diagnostics.error(e.pos(), "an invariant must be a condition, not " + Checker.describe(x.type()));
                return null;
            }
            return x;
        }

        private Edge edge(io.dtron.xta.ast.Edge e, Scope local, Map<String, Integer> byId, int index) {
            Integer source = e.source() == null ? null : byId.get(e.source());
            Integer target = e.target() == null ? null : byId.get(e.target());
            if (source == null || target == null) {
                String missing = source == null ? e.source() : e.target();
                diagnostics.error(e.pos(), "the edge's " + (source == null ? "source" : "target") + " '" + missing
                        + "' is not a location of template " + template.name());
                return null;
            }
            Frame frame = new Frame(0);
            Scope scope = new Scope(local);
            Checker checker = new Checker(compilation, scope, frame);
            boolean ok = true;
            if (branchpoints.contains(source)) {
                compilation.unsupported(e.pos(), "a branchpoint", "it is a probabilistic choice of statistical model"
                        + " checking, and the engine has no probabilities");
            }
            if (e.probability() != null) {
                ok &= probability(e, checker, branchpoints.contains(source));
            }
            List<Edge.Select> selects = new ArrayList<>();
            for (io.dtron.xta.ast.Edge.Select s : e.selects()) {
                Checker.Range range = checker.boundedRange(s.type(), "select '" + s.name() + "'");
                if (range == null) {
                    ok = false;
                    continue;
                }
                if (scope.local(s.name()) != null) {
                    diagnostics.error(s.pos(), "select '" + s.name() + "' is declared twice");
                    ok = false;
                    continue;
                }
                int slot = frame.allocate(1);
                scope.put(s.name(), new Symbol.Local(s.pos(), range.type(), slot, false, false));
                selects.add(new Edge.Select(s.name(), slot, range.type(), range.lower(), range.upper()));
            }
            Expression guard = null;
            if (e.guard() != null) {
                guard = guard(e.guard(), checker);
                ok &= guard != null;
            }
            Edge.Sync sync = null;
            if (e.sync() != null) {
                sync = sync(e.sync(), checker, guard);
                ok &= sync != null;
            }
            List<Expression> updates = new ArrayList<>();
            for (Expr u : e.updates()) {
                Expression x = checker.compile(u);
                if (x == null) {
                    ok = false;
                } else if (x.type() instanceof Type.ClockConstraint) {
                    diagnostics.error(u.pos(), "an update cannot be a clock constraint");
                    ok = false;
                } else {
                    updates.add(x);
                }
            }
            return ok ? new Edge(index, source, target, selects, guard, sync, updates, frame.size(), e.pos()) : null;
        }

        /** The weight of an edge leaving a branchpoint: a number without side effects. */
        private boolean probability(io.dtron.xta.ast.Edge e, Checker checker, boolean fromBranchpoint) {
            Expr w = e.probability();
            if (!fromBranchpoint) {
                diagnostics.warning(w.pos(), "a probability weight is ignored on an edge that does not leave a"
                        + " branchpoint");
                return true;
            }
            Expression x = checker.compile(w);
            if (x == null) {
                return false;
            }
            if (!Checker.isNumber(x.type())) {
                diagnostics.error(w.pos(), "a probability weight is a number, not " + Checker.describe(x.type()));
                return false;
            }
            if (checker.hasSideEffects(x)) {
                diagnostics.error(w.pos(), "a probability weight must not have side effects");
                return false;
            }
            return true;
        }

        private Expression guard(Expr e, Checker checker) {
            Expression x = checker.compile(e);
            if (x == null) {
                return null;
            }
            if (containsRate(x)) {
                diagnostics.error(e.pos(), "a clock rate (x' == e) can only stand in an invariant");
                return null;
            }
            if (checker.hasSideEffects(x)) {
                diagnostics.error(e.pos(), "a guard must not have side effects");
                return null;
            }
            if (x.type() instanceof Type.ClockConstraint c && c.kind() == Type.ConstraintKind.CONSTRAINT) {
                diagnostics.error(e.pos(), "a guard is a conjunction of clock bounds (x < c, x - y >= c, x == c) and"
                        + " conditions on data; '!=' on clocks, negations of clock constraints and disjunctions of two"
                        + " clock constraints are not allowed");
                return null;
            }
            if (!(x.type() instanceof Type.ClockConstraint) && !Checker.isInteger(x.type())) {
                diagnostics.error(e.pos(), "a guard must be a condition, not " + Checker.describe(x.type()));
                return null;
            }
            return x;
        }

        private Edge.Sync sync(io.dtron.xta.ast.Edge.Sync s, Checker checker, Expression guard) {
            Expression channel = checker.compile(s.channel());
            if (channel == null) {
                return null;
            }
            if (!(channel.type() instanceof Type.Channel kind)) {
                diagnostics.error(s.channel().pos(), "a synchronisation needs a channel, but '" + s.channel().pos().text()
                        + "' is " + Checker.describe(channel.type()));
                return null;
            }
            if (checker.hasSideEffects(channel)) {
                diagnostics.error(s.channel().pos(), "a synchronisation must not have side effects");
                return null;
            }
            if (kind.urgent() && guard != null && guard.type() instanceof Type.ClockConstraint) {
                // Uppaal warns ("clock guards are not allowed on urgent edges") and runs such an edge only in
                // statistical model checking, where it fires as soon as the guard holds
                compilation.unsupported(guard.pos(), "a clock guard on an edge that synchronises on an urgent channel",
                        "Uppaal allows it only in statistical model checking (its symbolic engine refuses it too), and"
                        + " the engine cannot let time pass while an urgent edge waits for its clock guard");
            }
            Edge.Direction direction = Edge.Direction.valueOf(s.direction().name());
            if (direction == Edge.Direction.CSP) {
                if (firstCsp == null) {
                    firstCsp = s.pos();
                }
            } else if (firstIo == null) {
                firstIo = s.pos();
            }
            return new Edge.Sync(channel, direction);
        }
    }

    // ================================================================ channel priorities

    private int[] channelPriorities(Decl.ChanPriority p, Checker checker) {
        int[] priority = new int[compilation.channelCount()];
        int defaultLevel = 0;
        for (int level = 0; level < p.levels().size(); level++) {
            for (Expr e : p.levels().get(level)) {
                if (e == null) {
                    defaultLevel = level;
                }
            }
        }
        java.util.Arrays.fill(priority, defaultLevel);
        for (int level = 0; level < p.levels().size(); level++) {
            for (Expr e : p.levels().get(level)) {
                if (e == null) {
                    continue;
                }
                Expression x = checker.compile(e);
                if (x == null) {
                    continue;
                }
                int[] range = channelRange(x);
                if (range == null) {
                    diagnostics.error(e.pos(), "a channel priority lists channels (or channel arrays), not '"
                            + e.pos().text() + "'");
                    continue;
                }
                for (int c = range[0]; c < range[1]; c++) {
                    priority[c] = level;
                }
            }
        }
        return priority;
    }

    private static int[] channelRange(Expression x) {
        if (x instanceof Expression.ChannelRef c) {
            ChannelVariable v = c.channel();
            return new int[] {v.index(), v.index() + v.type().channels()};
        }
        if (x instanceof Expression.Index i && i.index() instanceof Expression.Constant k
                && i.array().type() instanceof Type.Array a) {
            int[] outer = channelRange(i.array());
            if (outer == null) {
                return null;
            }
            int size = a.element().channels();
            int start = outer[0] + (k.value() - a.firstIndex()) * size;
            return new int[] {start, start + size};
        }
        return null;
    }
}
