package io.dtron.model.internal;

import io.dtron.model.Expression;
import io.dtron.model.Statement;
import io.dtron.model.Type;
import io.dtron.xta.ast.Decl;
import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.Stmt;
import java.util.ArrayList;
import java.util.List;

/** Compiles a function body, and finds out whether the function changes anything outside its frame. */
final class StatementCompiler {
    private final Diagnostics diagnostics;
    private final DeclarationCompiler declarations;
    private final Checker checker;
    private final FunctionInfo function;
    private int loops;

    StatementCompiler(Compilation compilation, DeclarationCompiler declarations, Checker checker,
                      FunctionInfo function) {
        this.diagnostics = compilation.diagnostics;
        this.declarations = declarations;
        this.checker = checker;
        this.function = function;
    }

    Statement.Block block(Stmt.Block b) {
        Scope outer = checker.scope();
        checker.enter(new Scope(outer));
        try {
            List<Statement> out = new ArrayList<>();
            for (Decl d : b.declarations()) {
                declarations.blockDeclaration(d, checker, out);
            }
            for (Stmt s : b.statements()) {
                Statement st = statement(s);
                if (st != null) {
                    out.add(st);
                }
            }
            return new Statement.Block(b.pos(), out);
        } finally {
            checker.leave(outer);
        }
    }

    private Statement statement(Stmt s) {
        if (s instanceof Stmt.Block b) {
            return block(b);
        } else if (s instanceof Stmt.Empty) {
            return null;
        } else if (s instanceof Stmt.ExprStmt e) {
            Expression x = effect(e.expr());
            return x == null ? null : new Statement.Eval(s.pos(), x);
        } else if (s instanceof Stmt.For f) {
            List<Expression> init = effects(f.init());
            Expression cond = f.condition() == null ? null : condition(f.condition());
            List<Expression> step = effects(f.step());
            Statement body = loop(f.body());
            return new Statement.For(s.pos(), init, cond, step, body == null ? empty(s) : body);
        } else if (s instanceof Stmt.Iteration it) {
            Checker.Range range = checker.boundedRange(it.type(), "'for (" + it.name() + " : T)'");
            if (range == null) {
                return null;
            }
            Scope outer = checker.scope();
            Scope inner = new Scope(outer);
            int slot = checker.frame().allocate(1);
            inner.put(it.name(), new Symbol.Local(it.pos(), range.type(), slot, false, false));
            checker.enter(inner);
            try {
                Statement body = loop(it.body());
                return new Statement.Iterate(s.pos(), slot, range.lower(), range.upper(), body == null ? empty(s) : body);
            } finally {
                checker.leave(outer);
            }
        } else if (s instanceof Stmt.While w) {
            Expression cond = condition(w.condition());
            Statement body = loop(w.body());
            return cond == null ? null : new Statement.While(s.pos(), cond, body == null ? empty(s) : body);
        } else if (s instanceof Stmt.DoWhile d) {
            Statement body = loop(d.body());
            Expression cond = condition(d.condition());
            return cond == null ? null : new Statement.DoWhile(s.pos(), body == null ? empty(s) : body, cond);
        } else if (s instanceof Stmt.If i) {
            Expression cond = condition(i.condition());
            Statement then = statement(i.then());
            Statement otherwise = i.otherwise() == null ? null : statement(i.otherwise());
            return cond == null ? null : new Statement.If(s.pos(), cond, then == null ? empty(s) : then, otherwise);
        } else if (s instanceof Stmt.Return r) {
            return ret(r);
        } else if (s instanceof Stmt.Break) {
            if (loops == 0) {
                diagnostics.error(s.pos(), "'break' outside a loop");
                return null;
            }
            return new Statement.Break(s.pos());
        } else if (s instanceof Stmt.Continue) {
            if (loops == 0) {
                diagnostics.error(s.pos(), "'continue' outside a loop");
                return null;
            }
            return new Statement.Continue(s.pos());
        } else {
            Expression cond = condition(((Stmt.Assert) s).condition());
            return cond == null ? null : new Statement.Assert(s.pos(), cond);
        }
    }

    private static Statement empty(Stmt s) {
        return new Statement.Block(s.pos(), List.of());
    }

    private Statement loop(Stmt body) {
        loops++;
        try {
            return statement(body);
        } finally {
            loops--;
        }
    }

    private Statement ret(Stmt.Return r) {
        Type expected = function.returnType;
        if (r.value() == null) {
            if (!(expected instanceof Type.Void)) {
                diagnostics.error(r.pos(), "'" + function.name + "' returns " + expected + ": 'return' needs a value");
                return null;
            }
            return new Statement.Return(r.pos(), null);
        }
        Expression value = effect(r.value());
        if (value == null) {
            return null;
        }
        if (expected instanceof Type.Void) {
            diagnostics.error(r.value().pos(), "'" + function.name + "' returns nothing (void), so 'return' takes no value");
            return null;
        }
        if (!Checker.assignable(expected, value)) {
            diagnostics.error(r.value().pos(), "'" + function.name + "' returns " + expected + ", not "
                    + Checker.describe(value.type()));
            return null;
        }
        return new Statement.Return(r.pos(), value);
    }

    private List<Expression> effects(List<Expr> exprs) {
        List<Expression> out = new ArrayList<>();
        for (Expr e : exprs) {
            Expression x = effect(e);
            if (x != null) {
                out.add(x);
            }
        }
        return out;
    }

    private Expression effect(Expr e) {
        Expression x = checker.compile(e);
        if (x != null && changesOutsideFrame(x)) {
            function.sideEffectFree = false;
        }
        if (x != null && x.type() instanceof Type.ClockConstraint) {
            diagnostics.error(e.pos(), "a clock constraint cannot be evaluated inside a function");
            return null;
        }
        return x;
    }

    private Expression condition(Expr e) {
        Expression x = effect(e);
        if (x != null && !Checker.isInteger(x.type())) {
            diagnostics.error(e.pos(), "a condition must be a boolean, not " + Checker.describe(x.type()));
            return null;
        }
        return x;
    }

    private boolean changesOutsideFrame(Expression e) {
        if (e instanceof Expression.Assign a) {
            return !isFrameLocal(a.target()) || changesOutsideFrame(a.value());
        }
        if (e instanceof Expression.Increment i) {
            return !isFrameLocal(i.target());
        }
        return checker.hasSideEffects(e) && !(e instanceof Expression.Assign);
    }

    private static boolean isFrameLocal(Expression target) {
        Expression root = target;
        while (true) {
            if (root instanceof Expression.Index i) {
                root = i.array();
            } else if (root instanceof Expression.FieldRef f) {
                root = f.struct();
            } else {
                break;
            }
        }
        return root instanceof Expression.LocalRef l && !l.reference();
    }

    /** Whether every path through the statement ends in a return. */
    static boolean alwaysReturns(Statement s) {
        if (s instanceof Statement.Return) {
            return true;
        }
        if (s instanceof Statement.Block b) {
            return b.statements().stream().anyMatch(StatementCompiler::alwaysReturns);
        }
        if (s instanceof Statement.If i) {
            return i.otherwise() != null && alwaysReturns(i.then()) && alwaysReturns(i.otherwise());
        }
        return false;
    }
}
