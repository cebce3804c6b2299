package io.dtron.xta.internal;

import io.dtron.xta.internal.parser.UppaalParser;
import org.antlr.v4.runtime.ParserRuleContext;
import org.antlr.v4.runtime.Token;
import org.antlr.v4.runtime.tree.ErrorNode;
import org.antlr.v4.runtime.tree.ParseTreeListener;
import org.antlr.v4.runtime.tree.TerminalNode;

/**
 * Stops the parser when expressions, statements, initialiser braces or types nest deeper than {@link #LEVELS}:
 * the parser, the AST builder and the checker all recurse once per level, so without a limit a deep enough
 * model would end in a stack overflow instead of an error with its place. An expression's level is the number
 * of expressions it is part of: parentheses and operators count. The parser reads a chain of left-associative
 * operators ({@code a + b + c}) in a loop, so this listener sees it as one level; {@link AstBuilder}, which
 * recurses into the chain's tree, applies the same limit to it.
 */
final class NestingLimit implements ParseTreeListener {
    /** The deepest nesting of each kind that a model may have. */
    static final int LEVELS = 1000;

    private int expressions;
    private int statements;
    private int initialisers;
    private int types;

    /** Nesting deeper than the limit, at the token where the level past the limit starts. */
    static final class TooDeep extends RuntimeException {
        private final transient Token token;

        TooDeep(String what, Token token) {
            super(message(what), null, false, false);
            this.token = token;
        }

        Token token() {
            return token;
        }
    }

    /** The error for nesting of {@code what} past the limit. */
    static String message(String what) {
        return what + " nested deeper than the limit of " + LEVELS + " levels";
    }

    /** Forgets the levels counted so far, for a new parse. */
    void reset() {
        expressions = 0;
        statements = 0;
        initialisers = 0;
        types = 0;
    }

    @Override
    public void enterEveryRule(ParserRuleContext ctx) {
        switch (ctx.getRuleIndex()) {
            case UppaalParser.RULE_expression -> check(++expressions, "expression", ctx);
            case UppaalParser.RULE_statement -> check(++statements, "statements", ctx);
            case UppaalParser.RULE_initialiser -> check(++initialisers, "initialiser braces", ctx);
            case UppaalParser.RULE_typeId -> check(++types, "types", ctx);
            default -> {
                // other rules do not nest in themselves
            }
        }
    }

    @Override
    public void exitEveryRule(ParserRuleContext ctx) {
        switch (ctx.getRuleIndex()) {
            case UppaalParser.RULE_expression -> expressions--;
            case UppaalParser.RULE_statement -> statements--;
            case UppaalParser.RULE_initialiser -> initialisers--;
            case UppaalParser.RULE_typeId -> types--;
            default -> {
                // not counted
            }
        }
    }

    private static void check(int level, String what, ParserRuleContext ctx) {
        if (level > LEVELS) {
            throw new TooDeep(what, ctx.getStart());
        }
    }

    @Override
    public void visitTerminal(TerminalNode node) {
        // tokens do not nest
    }

    @Override
    public void visitErrorNode(ErrorNode node) {
        // errors are reported by the error listener
    }
}
