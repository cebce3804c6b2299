package io.dtron.engine.internal.eval;

import io.dtron.model.Expression;
import io.dtron.xta.Pos;

/**
 * A compiled statement of a function body. {@link #exec} returns how control leaves it: {@link Env#NORMAL},
 * {@link Env#BREAK}, {@link Env#CONTINUE} or {@link Env#RETURN} (the value is then in {@link Env#ret}).
 */
abstract class StatementNode {

    abstract int exec(Env env);

    /** Statements in order. */
    static final class Block extends StatementNode {
        private final StatementNode[] statements;

        Block(StatementNode[] statements) {
            this.statements = statements;
        }

        @Override
        int exec(Env env) {
            for (StatementNode s : statements) {
                int status = s.exec(env);
                if (status != Env.NORMAL) {
                    return status;
                }
            }
            return Env.NORMAL;
        }
    }

    /** An expression evaluated for its effects. */
    static final class Eval extends StatementNode {
        private final ValueNode expression;

        Eval(ValueNode expression) {
            this.expression = expression;
        }

        @Override
        int exec(Env env) {
            expression.eval(env);
            return Env.NORMAL;
        }
    }

    /** Initialises an integer, boolean or scalar local. */
    static final class InitValue extends StatementNode {
        private final int slot;
        private final ValueNode value;
        private final Range range;
        private final Pos pos;

        InitValue(int slot, ValueNode value, Range range, Pos pos) {
            this.slot = slot;
            this.value = value;
            this.range = range;
            this.pos = pos;
        }

        @Override
        int exec(Env env) {
            int v = value.eval(env);
            if (!range.accepts(v)) {
                throw range.outside(pos, v, "'" + pos.text() + "'");
            }
            env.stack[env.bp + slot] = range.normalize(v);
            return Env.NORMAL;
        }
    }

    /** Initialises an array or struct local. */
    static final class InitCopy extends StatementNode {
        private final int slot;
        private final CopyNode value;

        InitCopy(int slot, CopyNode value) {
            this.slot = slot;
            this.value = value;
        }

        @Override
        int exec(Env env) {
            value.copyTo(env, env.varCount + env.bp + slot);
            return Env.NORMAL;
        }
    }

    /** {@code if}. */
    static final class If extends StatementNode {
        private final ValueNode condition;
        private final StatementNode then;
        private final StatementNode otherwise;

        If(ValueNode condition, StatementNode then, StatementNode otherwise) {
            this.condition = condition;
            this.then = then;
            this.otherwise = otherwise;
        }

        @Override
        int exec(Env env) {
            if (condition.eval(env) != 0) {
                return then.exec(env);
            }
            return otherwise == null ? Env.NORMAL : otherwise.exec(env);
        }
    }

    /** {@code while}. */
    static final class While extends StatementNode {
        private final ValueNode condition;
        private final StatementNode body;
        private final Pos pos;

        While(ValueNode condition, StatementNode body, Pos pos) {
            this.condition = condition;
            this.body = body;
            this.pos = pos;
        }

        @Override
        int exec(Env env) {
            while (condition.eval(env) != 0) {
                env.tick(pos);
                int status = body.exec(env);
                if (status == Env.BREAK) {
                    break;
                }
                if (status == Env.RETURN) {
                    return status;
                }
            }
            return Env.NORMAL;
        }
    }

    /** {@code do ... while}. */
    static final class DoWhile extends StatementNode {
        private final StatementNode body;
        private final ValueNode condition;
        private final Pos pos;

        DoWhile(StatementNode body, ValueNode condition, Pos pos) {
            this.body = body;
            this.condition = condition;
            this.pos = pos;
        }

        @Override
        int exec(Env env) {
            do {
                env.tick(pos);
                int status = body.exec(env);
                if (status == Env.BREAK) {
                    break;
                }
                if (status == Env.RETURN) {
                    return status;
                }
            } while (condition.eval(env) != 0);
            return Env.NORMAL;
        }
    }

    /** {@code for (init; condition; step)}; a null condition is true. */
    static final class For extends StatementNode {
        private final ValueNode[] init;
        private final ValueNode condition;
        private final ValueNode[] step;
        private final StatementNode body;
        private final Pos pos;

        For(ValueNode[] init, ValueNode condition, ValueNode[] step, StatementNode body, Pos pos) {
            this.init = init;
            this.condition = condition;
            this.step = step;
            this.body = body;
            this.pos = pos;
        }

        @Override
        int exec(Env env) {
            for (ValueNode e : init) {
                e.eval(env);
            }
            while (condition == null || condition.eval(env) != 0) {
                env.tick(pos);
                int status = body.exec(env);
                if (status == Env.BREAK) {
                    break;
                }
                if (status == Env.RETURN) {
                    return status;
                }
                for (ValueNode e : step) {
                    e.eval(env);
                }
            }
            return Env.NORMAL;
        }
    }

    /** {@code for (i : T)}. */
    static final class Iterate extends StatementNode {
        private final int slot;
        private final long lower;
        private final long upper;
        private final StatementNode body;
        private final Pos pos;

        Iterate(int slot, int lower, int upper, StatementNode body, Pos pos) {
            this.slot = slot;
            this.lower = lower;
            this.upper = upper;
            this.body = body;
            this.pos = pos;
        }

        @Override
        int exec(Env env) {
            for (long v = lower; v <= upper; v++) {
                env.tick(pos);
                env.stack[env.bp + slot] = (int) v;
                int status = body.exec(env);
                if (status == Env.BREAK) {
                    break;
                }
                if (status == Env.RETURN) {
                    return status;
                }
            }
            return Env.NORMAL;
        }
    }

    /** {@code return;} in a void function. */
    static final class ReturnVoid extends StatementNode {
        @Override
        int exec(Env env) {
            return Env.RETURN;
        }
    }

    /** {@code return e;} of an integer, boolean or scalar, checked against the return type. */
    static final class ReturnValue extends StatementNode {
        private final ValueNode value;
        private final Range range;
        private final String function;
        private final Expression source;

        ReturnValue(ValueNode value, Range range, String function, Expression source) {
            this.value = value;
            this.range = range;
            this.function = function;
            this.source = source;
        }

        @Override
        int exec(Env env) {
            int v = value.eval(env);
            if (!range.accepts(v)) {
                throw range.outside(source.pos(), v, "the return value of '" + function + "'");
            }
            env.ret = range.normalize(v);
            return Env.RETURN;
        }
    }

    /** {@code return e;} of an array or struct: copied to where the caller wants it. */
    static final class ReturnCopy extends StatementNode {
        private final CopyNode value;

        ReturnCopy(CopyNode value) {
            this.value = value;
        }

        @Override
        int exec(Env env) {
            value.copyTo(env, env.retAddr);
            return Env.RETURN;
        }
    }

    /** {@code break}. */
    static final class Break extends StatementNode {
        @Override
        int exec(Env env) {
            return Env.BREAK;
        }
    }

    /** {@code continue}. */
    static final class Continue extends StatementNode {
        @Override
        int exec(Env env) {
            return Env.CONTINUE;
        }
    }

    /** {@code assert}: a model error when false. */
    static final class Assert extends StatementNode {
        private final ValueNode condition;
        private final Expression source;

        Assert(ValueNode condition, Expression source) {
            this.condition = condition;
            this.source = source;
        }

        @Override
        int exec(Env env) {
            if (condition.eval(env) == 0) {
                throw new ModelRuntimeException(source.pos(), "the assertion '" + source.pos().text() + "' failed");
            }
            return Env.NORMAL;
        }
    }
}
