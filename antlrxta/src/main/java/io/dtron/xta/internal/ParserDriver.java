package io.dtron.xta.internal;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.Fragment;
import io.dtron.xta.Pos;
import io.dtron.xta.internal.parser.UppaalLexer;
import io.dtron.xta.internal.parser.UppaalParser;
import java.util.List;
import java.util.function.Consumer;
import java.util.function.Function;
import java.util.function.IntPredicate;
import org.antlr.v4.runtime.BailErrorStrategy;
import org.antlr.v4.runtime.CharStreams;
import org.antlr.v4.runtime.CommonTokenStream;
import org.antlr.v4.runtime.DefaultErrorStrategy;
import org.antlr.v4.runtime.ParserRuleContext;
import org.antlr.v4.runtime.Token;
import org.antlr.v4.runtime.TokenStream;
import org.antlr.v4.runtime.UnbufferedTokenStream;
import org.antlr.v4.runtime.atn.PredictionMode;
import org.antlr.v4.runtime.misc.ParseCancellationException;

/**
 * Runs the generated parser on one fragment: first in the fast SLL mode that bails out at the first
 * problem, then, only if that fails, in full LL mode with error recovery so that all syntax errors of the
 * fragment are reported. Long texts (declarations, system sections, whole {@code .xta} files) are parsed item
 * by item, each item's tree turned into AST and dropped before the next is read, so that the parse tree and the
 * tokens of a large section never are in memory at once. Nesting deeper than {@link NestingLimit#LEVELS} is a
 * model error.
 */
final class ParserDriver {
    private ParserDriver() {
    }

    /** The parse tree of the fragment by the given entry rule, or null with errors added to {@code out}. */
    static <T extends ParserRuleContext> T parse(Fragment fragment, Function<UppaalParser, T> rule,
                                                  List<Diagnostic> out) {
        UppaalLexer lexer = lexer(fragment);
        CommonTokenStream tokens = new CommonTokenStream(lexer);
        UppaalParser parser = sllParser(tokens);
        NestingLimit limit = new NestingLimit();
        parser.addParseListener(limit);
        try {
            try {
                return rule.apply(parser);
            } catch (ParseCancellationException bail) {
                tokens.seek(0);
                parser.reset();
                limit.reset();
                parser.getInterpreter().setPredictionMode(PredictionMode.LL);
                parser.setErrorHandler(new DefaultErrorStrategy());
                SyntaxErrorCollector collector = new SyntaxErrorCollector(fragment);
                parser.addErrorListener(collector);
                T tree = rule.apply(parser);
                if (collector.diagnostics().isEmpty()) {
                    return tree;
                }
                out.addAll(collector.diagnostics());
                return null;
            }
        } catch (NestingLimit.TooDeep e) {
            out.add(tooDeep(fragment, e));
            return null;
        }
    }

    /**
     * Parses {@code fragment} as a sequence of items, one at a time with {@code item} while {@code more} holds
     * for the next token's type (and it is not the end), then the rest with {@code end}. Each item and the end
     * go to {@code onItem} and {@code onEnd} as soon as they are parsed; their trees and tokens are dropped
     * after. Returns false when the text is not a clean sequence of items (a syntax error, or a construct the
     * item rule does not cover): the caller then drops what it built and parses the whole fragment with
     * {@link #parse}, which reports the errors as before. Nesting too deep is added to {@code out}, and returns
     * true.
     */
    static <C extends ParserRuleContext, E extends ParserRuleContext> boolean parseItems(
            Fragment fragment, Function<UppaalParser, C> item, IntPredicate more, Consumer<C> onItem,
            Function<UppaalParser, E> end, Consumer<E> onEnd, List<Diagnostic> out) {
        UnbufferedTokenStream tokens = new UnbufferedTokenStream(lexer(fragment));
        UppaalParser parser = sllParser(tokens);
        parser.addParseListener(new NestingLimit());
        try {
            while (tokens.LA(1) != Token.EOF && more.test(tokens.LA(1))) {
                onItem.accept(item.apply(parser));
            }
            onEnd.accept(end.apply(parser));
            return true;
        } catch (ParseCancellationException bail) {
            return false;
        } catch (NestingLimit.TooDeep e) {
            out.add(tooDeep(fragment, e));
            return true;
        }
    }

    private static UppaalLexer lexer(Fragment fragment) {
        UppaalLexer lexer = new UppaalLexer(CharStreams.fromString(fragment.text(), fragment.file()));
        lexer.removeErrorListeners();
        return lexer;
    }

    private static UppaalParser sllParser(TokenStream tokens) {
        UppaalParser parser = new UppaalParser(tokens);
        parser.removeErrorListeners();
        parser.getInterpreter().setPredictionMode(PredictionMode.SLL);
        parser.setErrorHandler(new BailErrorStrategy());
        return parser;
    }

    private static Diagnostic tooDeep(Fragment fragment, NestingLimit.TooDeep e) {
        Token at = e.token();
        int start = at.getType() == Token.EOF ? fragment.text().length() : at.getStartIndex();
        int end = at.getType() == Token.EOF ? start : at.getStopIndex() + 1;
        return Diagnostic.error(new Pos(fragment, start, end), e.getMessage());
    }
}
